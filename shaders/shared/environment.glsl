// Lat-long environment mapping: +y is up, u = 0.5 at −z; v = 1 at the zenith
// (texture origin bottom-left, like GL).
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
#include "constants.glsl"
SHARED_BEGIN

SHARED_FN vec2 latLongUv(vec3 dir) {
  float u = 0.5f + atan(dir.x, -dir.z) * INV_2PI;
  float v = 1.0f - acos(clamp(dir.y, -1.0f, 1.0f)) * INV_PI;
  return vec2(u, v);
}

SHARED_END
