// Voxel cone tracing's radiance injection (Dinse 2015 §3.1: the scene is
// voxelized with conservative rasterization and every fragment is lit with a
// diffuse direct-lighting model through the shadow map), per fragment of the
// three-axis conservative rasterization (voxelize/conservative.geom +
// conservative_cells.glsl): each cell the triangle overlaps (triangle–box
// test) takes the direct diffuse radiance leaving the triangle's point
// closest to the cell centre — both faces, through every light's shadow map
// (lightMapsDirect, the deferred direct pass's own function) — into the
// multi-valued grid's fixed-point radiance sums and counts
// (shared/value_grid.glsl), so voxelize/value_textures resolves and
// pre-integrates them like the atlas voxelizer's radiance channel.
// INJECT_DIRECTIONAL: also the direction it leaves in (each side's light
// along its side's normal; inject_sums.glsl: injectDirection).
// INJECT_MAX: the first pass, only the largest radiance (float bits, atomicMax:
// the fixed-point range of the second). INJECT_SVO: the sums are the sparse
// octree's leaves' (voxelize/sparse_octree.h; a cell's slot found by
// descending the tree; a cell not in the tree is left out, as the dense
// resolve leaves out a cell the binary grid does not hold).
#include "voxelize/conservative_cells.glsl"
#include "inject_pair.glsl"
flat in vec3 gWorldNormal;
flat in vec3 gWorld0;
flat in vec3 gWorld1;
flat in vec3 gWorld2;
flat in vec2 gUv0;
flat in vec2 gUv1;
flat in vec2 gUv2;

void visitCell(uvec3 c) {
  injectPair(c, gA, gB, gC, gWorld0, gWorld1, gWorld2, gUv0, gUv1, gUv2, gWorldNormal, gl_PrimitiveID);
}

void main() { visitTriangleCells(); }
