// The approximate visibility grid (Bashford-Rogers et al. 2011, §III-A; the
// `avg` module): per cell the sums of the unit normals and the albedos of the
// triangles that overlap it, and their count — summed (additively, as the
// paper blends), normalised where read. Fixed point so the GPU can add them
// with integer atomics: 8 uints per cell, x fastest then y then z:
//   0–2 Σ normal (two's-complement int, × avgFixedScale), 3–5 Σ albedo
//   (× avgFixedScale), 6 the count, 7 unused.
// At 2^16 per unit a cell holds 32767 triangles before a normal sum overflows.
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif

SHARED_BEGIN

SHARED_FN float avgFixedScale() { return 65536.0f; }
SHARED_FN uint avgCellBase(uvec3 c, uvec3 res) { return 8u * (c.x + res.x * (c.y + res.y * c.z)); }
// The mean of `count` fixed-point sums.
SHARED_FN vec3 avgMean(ivec3 sum, uint count) {
  return count == 0u ? vec3(0.0f) : vec3(sum) * (1.0f / (avgFixedScale() * float(count)));
}

SHARED_END
