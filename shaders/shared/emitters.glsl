// Area lights as the exact methods sample them, one source for the CPU
// (core/emitters.cpp) and the GL device (reference_gl, through the resource
// kind gpu_emitters): a point of an emissive triangle chosen in proportion to
// its power, then uniform on it, and the radiance a one- or two-sided emitter
// sends along a direction. PackedEmitter is the std430 row the GL side reads.
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
SHARED_BEGIN

// How the exact integrators sample area lights (parameter emitter_sampling):
// next-event estimation and BRDF sampling combined by MIS (power heuristic),
// or one of the two alone.
const int EMITTER_SAMPLING_MIS = 0;
const int EMITTER_SAMPLING_LIGHT = 1;
const int EMITTER_SAMPLING_BRDF = 2;

struct PackedEmitter {
  vec4 p0Cdf;        // xyz corner 0, w the power CDF up to and including this emitter
  vec4 e1CdfLo;      // xyz corner 1 − corner 0, w the CDF before it
  vec4 e2Area;       // xyz corner 2 − corner 0, w its area
  vec4 normalSides;  // xyz unit front normal (the winding's), w 1 where it emits from both sides
  vec4 radiance;     // xyz Le
};

// u.x rescaled into [0, 1) within the CDF interval [lo, lo + width) it fell in,
// so one stratified u both picks the triangle and places the point.
SHARED_FN float emitterRescale(float ux, float lo, float width) {
  return width > 0.0f ? clamp((ux - lo) / width, 0.0f, 1.0f - 1e-7f) : 0.5f;
}

// Uniform on the triangle p0 + b1·e1 + b2·e2 from (ux, uy) ∈ [0,1)²: Shirley
// and Chiu's square-root map, p0·(1 − √ux) + p1·√ux(1 − uy) + p2·√ux·uy.
SHARED_FN vec3 uniformTrianglePoint(vec3 p0, vec3 e1, vec3 e2, float ux, float uy) {
  const float su = sqrt(ux);
  const float b1 = su * (1.0f - uy), b2 = su * uy;
  return p0 + b1 * e1 + b2 * e2;
}

// Le leaving an emitter with unit front normal `normal` along unit `w` (away from it).
SHARED_FN vec3 emitterRadianceToward(vec3 normal, vec3 radiance, bool twoSided, vec3 w) {
  const float c = dot(normal, w);
  return (c > 0.0f || (twoSided && c < 0.0f)) ? radiance : vec3(0.0f);
}

SHARED_END
