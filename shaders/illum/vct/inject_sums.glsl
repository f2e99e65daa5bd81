// The sums the radiance injections write (inject.frag: per fragment;
// inject_texels.comp: per light-map texel), as shared/value_grid.glsl
// defines them: a count and fixed-point rgb sums per slot — a cell of the
// dense volume (x fastest) or, INJECT_SVO, a leaf of the sparse octree.
// INJECT_MAX: the first pass, which only takes the largest radiance (the
// fixed-point range of the second). INJECT_DIRECTIONAL: also the sums of the
// direction the light leaves in (shared/value_grid.glsl: decodeDirection), four
// words per slot. INJECT_CHECK_RANGE: the sums' pass with a range given (the
// last fill's) also takes the largest radiance, which the caller checks
// against it. INJECT_CELL_MAX: the sums' passes also keep per cell its pairs'
// largest radiance (float bits), from which a moving frame's range is taken
// (illum/vct/cell_max_reduce.comp). INJECT_REGION: only the pairs of the cells
// uRegionLo … uRegionHi − 1 (those a moving mesh and its shadow changed) are
// injected; every other cell has no slot in this pass. Needs
// voxelize/grid_uniforms.glsl's uResolution.
#include "shared/value_grid.glsl"
#ifdef INJECT_SVO
#include "shared/sparse_octree_lookup.glsl"
#endif
#if defined(INJECT_MAX) || defined(INJECT_CHECK_RANGE)
layout(std430, binding = BINDING_VALUE_RADIANCE_MAX) buffer RadianceMax { uint radianceMaxBits; };
#endif
#ifndef INJECT_MAX
layout(std430, binding = BINDING_VALUE_COUNTS) buffer Counts { uint counts[]; };
layout(std430, binding = BINDING_VALUE_RADIANCE) buffer RadianceSums { uint radianceSums[]; };
uniform float uRadianceMax;
#ifdef INJECT_DIRECTIONAL
layout(std430, binding = BINDING_VALUE_DIRECTION) buffer DirectionSums { uint directionSums[]; };
#endif
#endif

#ifdef INJECT_CELL_MAX
layout(std430, binding = BINDING_INJECT_CELL_MAX) buffer CellMax { uint cellMaxBits[]; };
#endif
#ifdef INJECT_REGION
uniform uvec3 uRegionLo;  // the cells injected: uRegionLo … uRegionHi − 1
uniform uvec3 uRegionHi;
#endif

const uint INJECT_NO_SLOT = 0xffffffffu;

// The slot of cell c, or INJECT_NO_SLOT where it has none (a cell outside the
// octree); the max pass has no slots (0).
uint injectSlot(uvec3 c) {
#if defined(INJECT_MAX)
  return 0u;
#elif defined(INJECT_SVO)
  return svoLeafSlot(c);
#else
#ifdef INJECT_REGION
  if (any(lessThan(c, uRegionLo)) || any(greaterThanEqual(c, uRegionHi))) return INJECT_NO_SLOT;
#endif
  return valueIndex(c, uvec4(uResolution.xyz, 0u), 0u) / 4u;
#endif
}

#if defined(INJECT_MAX) || defined(INJECT_CHECK_RANGE)
// The largest component of L into the pass' maximum. The word is read first and the atomic taken
// only when L is larger (one word for every fragment: the atomics contend); a stale read is smaller.
void injectMax(vec3 L) {
  uint bits = floatBitsToUint(max(L.x, max(L.y, L.z)));  // non-negative floats order as their bits
  if (bits > radianceMaxBits) atomicMax(radianceMaxBits, bits);
}
#endif

// Adds radiance L to slot `slot` (the max pass: to the maximum).
void injectAdd(uint slot, vec3 L) {
#ifdef INJECT_MAX
  injectMax(L);
#else
  atomicAdd(counts[slot], 1u);
  for (uint k = 0u; k < 3u; ++k) atomicAdd(radianceSums[4u * slot + k], toFixedRadiance(L[k], uRadianceMax));
#ifdef INJECT_CHECK_RANGE
  injectMax(L);  // was the range given this pass' maximum?
#endif
#ifdef INJECT_CELL_MAX
  uint bits = floatBitsToUint(max(L.x, max(L.y, L.z)));
  if (bits > cellMaxBits[slot]) atomicMax(cellMaxBits[slot], bits);
#endif
#endif
}

#if defined(INJECT_DIRECTIONAL) && !defined(INJECT_MAX)
// Adds the light leaving a surface of normal n: Lfront along n, Lback along −n.
void injectDirection(uint slot, vec3 n, vec3 Lfront, vec3 Lback) {
  float k = DIRECTION_FIXED_ONE / (3.0f * uRadianceMax);
  float front = (Lfront.x + Lfront.y + Lfront.z) * k, back = (Lback.x + Lback.y + Lback.z) * k;
  if (front + back <= 0.0f) return;
  ivec3 d = ivec3(round((front - back) * n));
  for (uint c = 0u; c < 3u; ++c)
    if (d[c] != 0) atomicAdd(directionSums[4u * slot + c], uint(d[c]));
  atomicAdd(directionSums[4u * slot + 3u], uint(round(front + back)));
}
#endif
