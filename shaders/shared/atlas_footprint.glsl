// The footprint of an atlas point (an extension of VGI §3.1's one point per
// texel): a texel stands for a small patch of its triangle, not only its
// centre. Point sampling misses cells that a triangle only clips at a corner
// or edge between two texel centres (recall ≈ 0.9–0.99 against the exact
// voxelizer however dense the atlas, docs/BENCHMARKS.md). Here each point also
// sets every cell within `radius` (world) of it — a cube — that its own
// triangle overlaps (the same float separating-axis test as the conservative
// voxelizer), so the grid stays a subset of the exact one while the patches
// between texel centres are covered. radius = 0 is the paper's single point.
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
#include "triangle_box.glsl"
#include "voxel_grid.glsl"
SHARED_BEGIN

// At most this many cells per axis are tested (a coarse atlas with a large
// footprint is clipped, not slowed down without bound).
const int kMaxFootprintCells = 4;

struct CellRange {
  ivec3 lo;
  ivec3 hi;  // inclusive; empty if any hi < lo
};

SHARED_FN CellRange footprintCells(SHARED_IN(GridParams) g, vec3 q, float radius) {
  vec3 r = radius * vec3(g.axisX.w, g.axisY.w, g.axisZ.w);  // in cells per axis
  CellRange c;
  c.lo = ivec3(max(floor(q - r), vec3(0.0f)));
  c.hi = ivec3(min(floor(q + r), vec3(g.resolution.x - 1u, g.resolution.y - 1u, g.resolution.z - 1u)));
  c.hi = min(c.hi, c.lo + ivec3(kMaxFootprintCells - 1));
  return c;
}

SHARED_END
