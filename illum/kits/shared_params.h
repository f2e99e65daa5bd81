// Parameters several methods share, read and documented once: the light
// maps' shadow test, the start offset of rays and cones, the environment
// beyond them, the own-voxel pass rule, the back-projection, and the default
// radii an approximate method and its exact counterpart (reference) must
// agree on.
#pragma once
#include <string>

#include "illum/framework/method.h"

namespace vgi {

class ParamSet;

// shadow_res, shadow_bias, normal_offset: the light maps of every GL method that reads them.
struct ShadowParams {
  int resolution = 1024;
  float bias = 1.0f, normalOffset = 0.0f;
};
void readShadowParams(ParamSet& params, ShadowParams& shadow);

// `offset`: how far along the normal the rays (or cones) of a voxel-tracing
// method start, in voxel diagonals — the guard against the receiver's own
// voxels. kDefaultOffset unless the method says why it differs (`why` joins
// the documentation).
constexpr float kDefaultOffset = 0.5f;
float readOffset(ParamSet& params, float def = kDefaultOffset, const std::string& why = "");
// `env`: whether what leaves the grid (nearfield: the radius) reads the scene's environment.
bool readEnv(ParamSet& params);
// `passthrough`: whether rays go on past a hit that may be the start's own
// voxel (within a voxel diagonal of its tangent plane); `rule`: the method's
// test for which hits those are.
bool readPassThrough(ParamSet& params, const std::string& rule);
// `backprojection`: the GLSL constant (shaders/illum/voxel_hit_params.glsl) of
// how a hit finds its RSM texel: plane (default) or entry (VGI).
int readBackProjection(ParamSet& params);

// `temporal`, `temporal_alpha`, `temporal_clamp`: the sample loop's temporal filter of an
// animation's frames (illum/framework/temporal.h), on by default with the defaults given.
TemporalSettings readTemporal(ParamSet& params, const TemporalSettings& defaults = {true});

// The near-field radius r as a fraction of the scene's diagonal, when not
// given: nearfield's and its exact counterpart's (reference integrator=nearfield).
constexpr float kDefaultNearFieldRadius = 0.5f;
// The AO radius as a fraction of the scene's diagonal, when not given:
// voxel_ao's, vct's and vct_ao's, and their counterpart's (reference integrator=ao).
constexpr float kDefaultAoRadius = 0.1f;

}  // namespace vgi
