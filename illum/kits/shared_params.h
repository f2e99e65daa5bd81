// Parameters several methods share, read and documented once: the light
// maps' shadow test, and the default radii an approximate method and its
// exact counterpart (reference) must agree on.
#pragma once

namespace vgi {

class ParamSet;

// shadow_res, shadow_bias, normal_offset: the light maps of every GL method that reads them.
struct ShadowParams {
  int resolution = 1024;
  float bias = 1.0f, normalOffset = 0.0f;
};
void readShadowParams(ParamSet& params, ShadowParams& shadow);

// The near-field radius r as a fraction of the scene's diagonal, when not
// given: nearfield's and its exact counterpart's (reference integrator=nearfield).
constexpr float kDefaultNearFieldRadius = 0.5f;
// The AO radius as a fraction of the scene's diagonal, when not given:
// voxel_ao's, vct's and vct_ao's, and their counterpart's (reference integrator=ao).
constexpr float kDefaultAoRadius = 0.1f;

}  // namespace vgi
