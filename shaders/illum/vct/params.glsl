// vct's pass parameters: one declaration for C++ (illum/methods/vct.cpp fills
// them) and GLSL (each pass's block Pass at UBO_PASS). Layout rule:
// illum/framework/compute_pass.h.
#ifdef __cplusplus
#pragma once
#include "../../shared/cpp_prelude.h"
#endif

SHARED_BEGIN

// diffuse.comp.glsl: the diffuse cones (a gather pass).
struct VctDiffuseParams {
  vec4 cones[16];     // the constellation: tangent-space axes (xyz), w the axis' cosine share
  float tanHalf;      // the diffuse cones' tan(aperture / 2)
  float maxDistance;  // a cone's length, world units
  float offset;       // apex offset along the normal, world units
  float aoRadius;     // AO: occlusion counts within this distance
  float falloff;      // AO: λ of 1/(1 + λ t / radius)
  float turn;         // the constellation's azimuth this sample
  float setTurn;      // … plus this per interleave set (k×k blocks, the kit's blur averages them)
  int sets;           // k
  int env;            // cones leaving the grid see the environment
  float diffuse;      // 1, or 0 with diffuse=false (the cones then give the AO alone)
  int guard;          // cones.glsl's receiver guard
  int pad0;
};

// shade.comp.glsl: specular cone, cone-traced shadows, the AO output.
struct VctShadeParams {
  vec4 cameraPosition;  // xyz, this sample's
  int specular;         // the specular cone
  int shadows;          // cone-traced shadows of the delta lights
  int skipEmpty;        // the specular cone skips empty space
  int env;              // cones leaving the grid see the environment
  float shadowBias;     // the direct pass' (texels)
  float normalOffset;   // the direct pass' (texels)
  float shadowTanHalf;  // the shadow cones' tan(aperture / 2)
  float offset;         // apex offset along the normal, world units
  float maxDistance;    // the specular cone's length
  float voxelDiagonal;  // world units
  float shadowStop;     // shadow cones end this many widths before the light
  int guard;            // cones.glsl's receiver guard
  int writeIndirect;    // the AOVs asked for
  int writeDirect;
  int writeAo;
  int writeSpecular;
};

SHARED_END
