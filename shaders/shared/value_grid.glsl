// Multi-valued grids (VGI §3, averaging as in Bashford-Rogers et al., AVG §3):
// every atlas point adds its values to its cell as 16-bit fixed point into
// 32-bit sums with atomicAdd, and counts itself; the mean is sum / count.
// Channels: normal (range −1…1), albedo (0…1), glossy (ks 0…1; the Phong
// exponent as log2(1 + e) over 0…log2(1 + GLOSSY_MAX_EXPONENT), so small and
// large exponents keep the same relative precision; its mean is taken in that
// log space).
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
SHARED_BEGIN

const float FIXED_ONE = 65535.0f;
const float GLOSSY_MAX_EXPONENT = 100000.0f;

// v in [lo, hi] → 0 … 65535.
SHARED_FN uint toFixed(float v, float lo, float hi) {
  return uint(clamp((v - lo) / (hi - lo), 0.0f, 1.0f) * FIXED_ONE + 0.5f);
}

SHARED_FN float fromFixedMean(uint sum, uint count, float lo, float hi) {
  return lo + (hi - lo) * (float(sum) / (float(count) * FIXED_ONE));
}

SHARED_FN float encodeExponent(float e) { return log2(1.0f + max(e, 0.0f)); }
SHARED_FN float decodeExponent(float x) { return exp2(x) - 1.0f; }
SHARED_FN float exponentCodeMax() { return log2(1.0f + GLOSSY_MAX_EXPONENT); }

// Index of component c (0…3) of a cell's sums, cells in x-fastest order.
SHARED_FN uint valueIndex(uvec3 cell, uvec4 resolution, uint c) {
  return ((cell.z * resolution.y + cell.y) * resolution.x + cell.x) * 4u + c;
}

SHARED_END
