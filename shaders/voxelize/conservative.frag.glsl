// Three-axis conservative voxelization, per fragment: the cells the triangle
// overlaps in this pixel's column (conservative_cells.glsl) set in the grid.
#include "shared/voxel_grid.glsl"
#include "shared/bindings.glsl"
#include "conservative_cells.glsl"
layout(std430, binding = BINDING_GRID_WORDS) buffer Columns { uint words[]; };
void visitCell(uvec3 c) { atomicOr(words[columnWordIndex(c.x, c.y, depthWord(c.z), uResolution)], depthBit(c.z)); }
void main() { visitTriangleCells(); }
