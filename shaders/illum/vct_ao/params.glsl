// vct_ao's gather pass parameters: one declaration for C++ (illum/methods/vct_ao.cpp fills
// them) and GLSL (ao.comp.glsl's block Pass at UBO_PASS). Layout rule:
// illum/framework/compute_pass.h.
#ifdef __cplusplus
#pragma once
#include "../../shared/cpp_prelude.h"
#endif

SHARED_BEGIN

struct VctAoParams {
  vec4 cones[16];  // the constellation: tangent-space axes (xyz), w the axis' cosine share
  float tanHalf;   // tan(aperture / 2), the overlap factor applied
  float radius;    // cone length r, world units
  float offset;    // origin offset along the normal, world units
  float falloff;   // λ
  float turn;      // the constellation's azimuth this sample
  float jitter;    // the per-pixel azimuth's range (radians; 0: none)
  uint seed;
  int guard;  // cones.glsl's receiver guard
};

SHARED_END
