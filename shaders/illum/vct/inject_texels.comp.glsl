// Radiance injection as the 2013 article does it (../shared/papers/002_…;
// Crassin et al. 2011 §4.1): every texel of the light maps (reflective shadow
// maps) where the light saw a surface adds the surface's diffusely reflected
// direct radiance (the RSM's, the same quantity inject.frag computes per
// fragment) to the cell its position falls in — the dense volume's cells or,
// INJECT_SVO, the octree's leaves — as the same fixed-point sums
// (shared/value_grid.glsl). Cells no texel lands in keep no light: the holes
// where the maps are coarser than the voxels. INJECT_MAX: the first pass, the
// largest radiance (the fixed-point range).
#include "../../shared/constants.glsl"
#include "../../shared/sampling.glsl"
#include "../../shared/brdf.glsl"
#include "../../shared/environment.glsl"
#include "../../shared/gpu_scene.glsl"
#include "../../shared/light_maps.glsl"
#include "../../shared/value_grid.glsl"
#include "../../voxelize/grid_uniforms.glsl"
#ifdef INJECT_SVO
#include "../../shared/svo_lookup.glsl"
#endif
layout(local_size_x = 8, local_size_y = 8) in;
#ifdef INJECT_MAX
layout(std430, binding = BINDING_VALUE_RADIANCE_MAX) buffer RadianceMax { uint radianceMaxBits; };
#else
layout(std430, binding = BINDING_VALUE_COUNTS) buffer Counts { uint counts[]; };
layout(std430, binding = BINDING_VALUE_RADIANCE) buffer RadianceSums { uint radianceSums[]; };
uniform float uRadianceMax;
#endif
uniform int uMapResolution;
void main() {
  ivec3 id = ivec3(gl_GlobalInvocationID);
  if (id.x >= uMapResolution || id.y >= uMapResolution) return;
  RsmVpl v = rsmTexelVpl(id.z, id.xy);
  if (!v.valid) return;
  vec3 q = worldToGrid(gridFromUniforms(), v.position);
  if (any(lessThan(q, vec3(0.0f))) || any(greaterThanEqual(q, vec3(uResolution.xyz)))) return;
  uvec3 c = uvec3(q);
#ifdef INJECT_MAX
  atomicMax(radianceMaxBits, floatBitsToUint(max(v.radiance.x, max(v.radiance.y, v.radiance.z))));
#else
#ifdef INJECT_SVO
  uint slot = svoLeafSlot(c);
  if (slot == SVO_NO_SLOT) return;
#else
  uint slot = valueIndex(c, uvec4(uResolution.xyz, 0u), 0u) / 4u;
#endif
  atomicAdd(counts[slot], 1u);
  for (uint k = 0u; k < 3u; ++k) atomicAdd(radianceSums[4u * slot + k], toFixedRadiance(v.radiance[k], uRadianceMax));
#endif
}
