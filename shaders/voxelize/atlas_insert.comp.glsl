// Binary atlas voxelization, insertion (VGI §3.1): one point per valid atlas
// texel sets the bit of its cell with atomicOr — plus, with a footprint, the
// nearby cells its triangle overlaps (atlas_point_cells.glsl). The CPU build
// (insertAtlasPoints) runs the same shared kernels.
#include "grid_uniforms.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
#include "atlas_insert_bits.glsl"
void visitCell(ivec2 texel, uvec3 c) { setCellBit(c); }
#include "atlas_point_cells.glsl"
void main() {
  ivec2 t;
  if (!insertionTexel(t)) return;
  if (visitPointCells(t)) atomicAdd(points, 1u);
}
