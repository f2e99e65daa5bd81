// The sums the radiance injections write (inject.frag: per fragment;
// inject_texels.comp: per light-map texel), as shared/value_grid.glsl
// defines them: a count and fixed-point rgb sums per slot — a cell of the
// dense volume (x fastest) or, INJECT_SVO, a leaf of the sparse octree.
// INJECT_MAX: the first pass, which only takes the largest radiance (the
// fixed-point range of the second). INJECT_DIRECTIONAL: also the sums of the
// direction the light leaves in (shared/value_grid.glsl: decodeDirection), four
// words per slot. Needs voxelize/grid_uniforms.glsl's uResolution.
#include "shared/value_grid.glsl"
#ifdef INJECT_SVO
#include "shared/sparse_octree_lookup.glsl"
#endif
#ifdef INJECT_MAX
layout(std430, binding = BINDING_VALUE_RADIANCE_MAX) buffer RadianceMax { uint radianceMaxBits; };
#else
layout(std430, binding = BINDING_VALUE_COUNTS) buffer Counts { uint counts[]; };
layout(std430, binding = BINDING_VALUE_RADIANCE) buffer RadianceSums { uint radianceSums[]; };
uniform float uRadianceMax;
#ifdef INJECT_DIRECTIONAL
layout(std430, binding = BINDING_VALUE_DIRECTION) buffer DirectionSums { uint directionSums[]; };
#endif
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
  return valueIndex(c, uvec4(uResolution.xyz, 0u), 0u) / 4u;
#endif
}

// Adds radiance L to slot `slot` (the max pass: to the maximum).
void injectAdd(uint slot, vec3 L) {
#ifdef INJECT_MAX
  atomicMax(radianceMaxBits, floatBitsToUint(max(L.x, max(L.y, L.z))));
#else
  atomicAdd(counts[slot], 1u);
  for (uint k = 0u; k < 3u; ++k) atomicAdd(radianceSums[4u * slot + k], toFixedRadiance(L[k], uRadianceMax));
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
