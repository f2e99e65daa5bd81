// Multi-valued grids (VGI §3, averaging as in Bashford-Rogers et al., AVG §3):
// every atlas point adds its values to its cell as 16-bit fixed point into
// 32-bit sums with atomicAdd, and counts itself; the mean is sum / count.
// Channels: normal (range −1…1), albedo (0…1), glossy (ks 0…1; the Phong
// exponent as log2(1 + e) over 0…log2(1 + GLOSSY_MAX_EXPONENT), so small and
// large exponents keep the same relative precision; its mean is taken in that
// log space), radiance (VGI §3, Table 2: the diffuse direct light leaving each
// atlas point; 0…the measured maximum of the pass in 20-bit steps, so a cell
// holds up to 4096 points before its 32-bit sum could overflow).
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
#include "voxel_grid.glsl"
SHARED_BEGIN

const float FIXED_ONE = 65535.0f;
const float GLOSSY_MAX_EXPONENT = 100000.0f;
const float RADIANCE_FIXED_ONE = 1048575.0f;  // 2^20 − 1
const uint RADIANCE_MAX_POINTS_PER_CELL = 4096u;

// v in [lo, hi] → 0 … 65535.
SHARED_FN uint toFixed(float v, float lo, float hi) {
  return uint(clamp((v - lo) / (hi - lo), 0.0f, 1.0f) * FIXED_ONE + 0.5f);
}

SHARED_FN float fromFixedMean(uint sum, uint count, float lo, float hi) {
  return lo + (hi - lo) * (float(sum) / (float(count) * FIXED_ONE));
}

// Radiance v in [0, maxRadiance] → 0 … 2^20 − 1 (clamped), and the mean back.
SHARED_FN uint toFixedRadiance(float v, float maxRadiance) {
  return uint(clamp(v / maxRadiance, 0.0f, 1.0f) * RADIANCE_FIXED_ONE + 0.5f);
}
SHARED_FN vec4 decodeRadianceMean(uvec4 sums, uint count, float maxRadiance) {
  float k = maxRadiance / (float(count) * RADIANCE_FIXED_ONE);
  return vec4(float(sums.x) * k, float(sums.y) * k, float(sums.z) * k, 0.0f);
}

// A cell's premultiplied radiance (L·α, α) from its sums and count: 0 where it
// is empty, (0, 0, 0, 1) where it is occupied without points (the dense
// volume's resolve and the sparse octree's leaves both call this).
SHARED_FN vec4 premultipliedRadiance(uvec4 sums, uint count, bool occupied, float maxRadiance) {
  if (!occupied) return vec4(0.0f);
  if (count == 0u) return vec4(0.0f, 0.0f, 0.0f, 1.0f);
  return decodeRadianceMean(sums, count, maxRadiance) + vec4(0.0f, 0.0f, 0.0f, 1.0f);
}

SHARED_FN float encodeExponent(float e) { return log2(1.0f + max(e, 0.0f)); }
SHARED_FN float decodeExponent(float x) { return exp2(x) - 1.0f; }
SHARED_FN float exponentCodeMax() { return log2(1.0f + GLOSSY_MAX_EXPONENT); }

// Index of component c (0…3) of a cell's sums, cells in x-fastest order.
SHARED_FN uint valueIndex(uvec3 cell, uvec4 resolution, uint c) {
  return ((cell.z * resolution.y + cell.y) * resolution.x + cell.x) * 4u + c;
}

const uint VALUE_CHANNEL_NORMAL = 0u;
const uint VALUE_CHANNEL_ALBEDO = 1u;
const uint VALUE_CHANNEL_GLOSSY = 2u;
const uint VALUE_CHANNEL_RADIANCE = 3u;  // decoded by decodeRadianceMean

// The mean of a cell's sums (count > 0) of channel ch: normal in −1…1 (not
// renormalised: its length < 1 measures the spread), albedo and ks in 0…1, the
// glossy exponent as its code log2(1 + e) (decodeExponent gives e), so means
// and filtering happen in that log space. The CPU decode and the GPU resolve
// both call this: their means are the same floats.
SHARED_FN vec4 decodeValueMean(uvec4 sums, uint count, uint ch) {
  float lo = ch == VALUE_CHANNEL_NORMAL ? -1.0f : 0.0f;
  vec4 m = vec4(fromFixedMean(sums.x, count, lo, 1.0f), fromFixedMean(sums.y, count, lo, 1.0f),
                fromFixedMean(sums.z, count, lo, 1.0f), 0.0f);
  if (ch == VALUE_CHANNEL_GLOSSY) m.w = fromFixedMean(sums.w, count, 0.0f, exponentCodeMax());
  return m;
}

// ---- The 3D textures (voxelize/value_textures.h) and their mip chains.

// Texture coordinates of world point p in the grid's 3D textures.
SHARED_FN vec3 valueUvw(SHARED_IN(GridParams) g, vec3 p) {
  vec3 q = worldToGrid(g, p);
  return vec3(q.x / float(g.resolution.x), q.y / float(g.resolution.y), q.z / float(g.resolution.z));
}

// One isotropic mip texel: the plain mean of its 2×2×2 children (empty
// children are 0 in every channel and in the occupancy, so channel / occupancy
// is the occupancy-weighted mean at every level).
SHARED_FN vec4 boxMean8(vec4 a, vec4 b, vec4 c, vec4 d, vec4 e, vec4 f, vec4 g, vec4 h) {
  SHARED_PRECISE vec4 s = ((a + b) + (c + d)) + ((e + f) + (g + h));
  return s * 0.125f;
}

// Front-to-back composition of premultiplied colours with alpha in w.
SHARED_FN vec4 frontToBack(vec4 front, vec4 back) {
  SHARED_PRECISE vec4 r = front + (1.0f - front.w) * back;
  return r;
}

// Six-direction anisotropic mip texel (Crassin et al. 2011; Dinse 2015,
// §3.2): for travel along face f's direction (f = 2·axis, +1 for the negative
// direction), each of the four lines of children along that axis is composed
// front to back, and the four results are averaged. Children are indexed
// x + 2y + 4z.
SHARED_FN vec4 anisoReduce(vec4 c[8], uint face) {
  uint bit = 1u << (face >> 1u);
  bool positive = (face & 1u) == 0u;
  vec4 sum = vec4(0.0f);
  for (uint i = 0u; i < 8u; ++i) {
    if ((i & bit) != 0u) continue;  // i: the line's lower child
    vec4 lo = c[i];
    vec4 hi = c[i | bit];
    sum = sum + (positive ? frontToBack(lo, hi) : frontToBack(hi, lo));
  }
  return sum * 0.25f;
}

// Directional level-0 radiance (vct's `directional`; ours): per cell D =
// Σ (ℓ⁺ − ℓ⁻) n / Σ (ℓ⁺ + ℓ⁻) over its (triangle, cell) pairs, ℓ± the
// luminance (mean of rgb) of the light leaving the triangle's side ±n, so
// |D| ≤ 1: a wall lit on one side only has D = its lit side's normal, one lit
// alike on both sides D = 0. A cell's radiance seen from direction w (unit,
// towards the viewer) is its mean times min(1, 1 + w·D): unchanged from the
// side D points to and edge-on, 1 − |D| of it straight from behind, so a wall
// voxel whose one face is lit does not glow into the room behind it (the
// cosine lobe (1 + w·D) / (1 + |D|) halved every wall seen edge-on:
// docs/BENCHMARKS.md, "Leaks: vct").
// The sums are fixed point (DIRECTION_FIXED_ONE per unit of radiance / the
// pass' maximum) in 32-bit words: xyz signed (two's complement), w unsigned.
const float DIRECTION_FIXED_ONE = 65535.0f;
SHARED_FN float directionalFacing(vec3 towardsViewer, vec3 D) {
  return min(1.0f + dot(towardsViewer, D), 1.0f);
}
// D from a cell's sums (0 where nothing was lit).
SHARED_FN vec3 decodeDirection(uvec4 sums) {
  if (sums.w == 0u) return vec3(0.0f);
  vec3 d = vec3(float(int(sums.x)), float(int(sums.y)), float(int(sums.z))) / float(sums.w);
  float len = length(d);
  return len > 1.0f ? d / len : d;  // rounding of the fixed point
}
// The unit direction a cone travels along to read face f (f = 2·axis, +1 negative).
SHARED_FN vec3 anisoFaceTravel(uint face) {
  vec3 t = vec3(0.0f);
  t[face >> 1u] = (face & 1u) == 0u ? 1.0f : -1.0f;
  return t;
}

// Looking up an anisotropic chain along unit direction d: the three faces
// facing d (anisoFaces) weighted by d² (anisoWeights, summing to 1).
SHARED_FN uvec3 anisoFaces(vec3 d) {
  return uvec3(d.x >= 0.0f ? 0u : 1u, d.y >= 0.0f ? 2u : 3u, d.z >= 0.0f ? 4u : 5u);
}
SHARED_FN vec3 anisoWeights(vec3 d) { return d * d; }

SHARED_END
