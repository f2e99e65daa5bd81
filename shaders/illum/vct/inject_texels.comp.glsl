// Radiance injection as the 2013 article does it (../shared/papers/002_…;
// Crassin et al. 2011 §4.1): every texel of the light maps (reflective shadow
// maps) where the light saw a surface adds the surface's diffusely reflected
// direct radiance (the RSM's, the same quantity inject.frag computes per
// fragment) to the cell its position falls in — the dense volume's cells or,
// INJECT_SVO, the octree's leaves — as the same fixed-point sums
// (shared/value_grid.glsl). Cells no texel lands in keep no light: the holes
// where the maps are coarser than the voxels. INJECT_MAX: the first pass, the
// largest radiance (the fixed-point range).
#include "shared/constants.glsl"
#include "shared/sampling.glsl"
#include "shared/brdf.glsl"
#include "shared/environment.glsl"
#include "shared/gpu_scene.glsl"
#include "shared/light_maps.glsl"
#include "voxelize/grid_uniforms.glsl"
#include "inject_sums.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
uniform int uMapResolution;
void main() {
  ivec3 id = ivec3(gl_GlobalInvocationID);
  if (id.x >= uMapResolution || id.y >= uMapResolution) return;
  RsmVpl v = rsmTexelVpl(id.z, id.xy);
  if (!v.valid) return;
  vec3 q = worldToGrid(gridFromUniforms(), v.position);
  if (any(lessThan(q, vec3(0.0f))) || any(greaterThanEqual(q, vec3(uResolution.xyz)))) return;
  uint slot = injectSlot(uvec3(q));
  if (slot != INJECT_NO_SLOT) injectAdd(slot, v.radiance);
}
