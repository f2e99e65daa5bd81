// Delta lights (point, spot, directional) as one std430 struct, and the
// radiance they deliver to a point. The GL modules read the struct from an SSBO;
// the CPU reference packs the same struct, so both evaluate identical lights.
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
#include "constants.glsl"
SHARED_BEGIN

const uint LIGHT_POINT = 0u;
const uint LIGHT_SPOT = 1u;
const uint LIGHT_DIRECTIONAL = 2u;

struct PackedLight {
  vec4 positionType;        // xyz position, w = type
  vec4 directionCosCone;    // xyz spot axis / direction of travel, w = cos(cone half-angle)
  vec4 intensityFalloff;    // xyz intensity (W/sr) or irradiance, w = spot falloff exponent
};

struct LightSample {
  vec3 wi;        // unit direction from the point towards the light
  float dist;     // distance to the light (1e30 for directional)
  vec3 radiance;  // incident radiance-like term: multiply by f·cos θ (no pdf: delta light)
};

SHARED_FN LightSample sampleDeltaLight(PackedLight L, vec3 p) {
  LightSample s;
  uint type = uint(L.positionType.w + 0.5f);
  vec3 intensity = vec3(L.intensityFalloff.x, L.intensityFalloff.y, L.intensityFalloff.z);
  if (type == LIGHT_DIRECTIONAL) {
    s.wi = -vec3(L.directionCosCone.x, L.directionCosCone.y, L.directionCosCone.z);
    s.dist = 1e30f;
    s.radiance = intensity;
    return s;
  }
  vec3 d = vec3(L.positionType.x, L.positionType.y, L.positionType.z) - p;
  float dist2 = max(dot(d, d), 1e-20f);
  s.dist = sqrt(dist2);
  s.wi = d / s.dist;
  s.radiance = intensity / dist2;
  if (type == LIGHT_SPOT) {
    vec3 axis = vec3(L.directionCosCone.x, L.directionCosCone.y, L.directionCosCone.z);
    float cosT = -dot(s.wi, axis);
    // cos θ < cos(cone) is outside; at a 90° cone the boundary is cos θ = 0.
    if (cosT < L.directionCosCone.w || cosT <= 0.0f) {
      s.radiance = vec3(0.0f);
    } else if (L.intensityFalloff.w > 0.0f) {
      s.radiance = s.radiance * pow(cosT, L.intensityFalloff.w);
    }
  }
  return s;
}

SHARED_END
