// The OR-mip pyramid over the column grid (VGI §4): level l+1 holds, per
// column, the OR of the (up to) 2×2 columns below it; the depth resolution is
// the same at every level (a texel is a whole column). Sizes halve rounding up
// (W → ⌈W/2⌉) down to 1×1. All levels sit in one word array, level after level,
// each laid out like shaders/shared/voxel_grid.glsl (slab-major columns).
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
#include "voxel_grid.glsl"
#include "bindings.glsl"
SHARED_BEGIN

const uint kMaxPyramidLevels = 16u;

// What a tracer needs to read a pyramid: the grid and where each level starts
// in the word array (level 0 is the grid itself, at offset 0).
struct PyramidParams {
  GridParams grid;
  uint levels;
  uint levelOffsets[16];
};

SHARED_FN uvec2 mipLevelSize(uvec2 base, uint level) {
  uvec2 s = base;
  for (uint i = 0u; i < level; ++i) s = uvec2((s.x + 1u) >> 1u, (s.y + 1u) >> 1u);
  return s;
}

// Index of word w of column (x, y) of a level of size `size`, starting at
// `levelOffset` words into the pyramid; depth D is the same on every level.
SHARED_FN uint mipWordIndex(uint x, uint y, uint w, uvec2 size, uint depth, uint levelOffset) {
  return levelOffset + columnWordIndex(x, y, w, uvec4(size.x, size.y, depth, depth / 128u));
}

// The pyramid seen from its level `level` (< p.levels) up: that level is its
// level 0, its grid that level's grid — columns 2^level level-0 cells wide in
// x and y, the same depth cells. Any tracer then traces the level's columns
// as voxels (the `voxels` debug view of a mip level, and its tests). The
// cells-per-unit scale by a power of two, so the level's planes are exactly
// the level-0 planes at multiples of 2^level; the level's box is
// ⌈W/2^level⌉·2^level level-0 cells wide (its last column reaches past W).
SHARED_FN PyramidParams pyramidFromLevel(SHARED_IN(PyramidParams) p, uint level) {
  PyramidParams q = p;
  const float scale = 1.0f / float(1u << level);
  q.grid.axisX.w = p.grid.axisX.w * scale;
  q.grid.axisY.w = p.grid.axisY.w * scale;
  const uvec2 s = mipLevelSize(uvec2(p.grid.resolution.x, p.grid.resolution.y), level);
  q.grid.resolution.x = s.x;
  q.grid.resolution.y = s.y;
  q.levels = p.levels - level;
  for (uint i = 0u; i < kMaxPyramidLevels; ++i) q.levelOffsets[i] = i < q.levels ? p.levelOffsets[i + level] : 0u;
  return q;
}

SHARED_END
