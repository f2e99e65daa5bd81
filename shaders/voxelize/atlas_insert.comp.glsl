// Binary atlas voxelization, insertion (VGI §3.1): one point per valid atlas
// texel sets the bit of its cell with atomicOr — plus, with a footprint, the
// nearby cells its triangle overlaps (atlas_point_cells.glsl). The CPU build
// (insertAtlasPoints) runs the same shared kernels.
#include "grid_uniforms.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
#include "shared/bindings.glsl"
layout(std430, binding = BINDING_GRID_WORDS) buffer Columns { uint words[]; };
layout(std430, binding = BINDING_VOXEL_COUNTER) buffer Counters { uint points; };
void visitCell(ivec2 texel, uvec3 c) {
  atomicOr(words[columnWordIndex(c.x, c.y, depthWord(c.z), uResolution)], depthBit(c.z));
}
#include "atlas_point_cells.glsl"
void main() {
  ivec2 t = ivec2(gl_GlobalInvocationID.xy);
  if (t.x >= uAtlasSize.x || t.y >= uAtlasSize.y) return;
  if (visitPointCells(t)) atomicAdd(points, 1u);
}
