// 4³ bricks over the binary grid (issue "Speed on the GL device", step 4): the OR-reduction of the grid
// taken 4×4×4 cells at a time, so one 64-bit mask (two words) says which of a node's 4³ children hold
// geometry — the node of a sparse 64-tree (Laine & Karras, "Efficient Sparse Voxel Octrees", 2010, use
// 2³ children; 4³ children halve the levels and skip empty space in bigger steps, as brickmaps do). The
// levels are dense, like the OR-mip pyramid's: brick level s ≥ 1 has bricksPerAxis(n, s) nodes on an
// axis of n cells; node (x, y, z) covers cells [x·4^s, (x+1)·4^s) on x (likewise y, z), and its bit
// i + 4j + 16k says whether child (i, j, k) — the 4^(s−1)-cell cube at (4x + i, 4y + j, 4z + k)·4^(s−1)
// — holds a set cell. Level 0 is the grid itself (a 4^0 cube is a voxel). Children past the grid's edge
// are empty. Unlike the OR-mip pyramid's columns (2×2 in x, y, the depth kept) a brick reduces depth too.
//
// The masks: brickNodeMask, one kernel for the CPU builder (traverse/brick_tree.cpp) and a GPU one; the
// tracer that reads them: trace_bricks.glsl. The grid's words and the bricks' words are two arrays:
// GRID_WORDS / brickWords (BRICK_PARAM / BRICK_ARG).
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
// The grid's words and the bricks' words: pointers in C++, buffers gridWords and brickWords in GLSL.
#define BRICK_PARAM , const uint *gridWords, const uint *brickWords
#define BRICK_ARG , gridWords, brickWords
#endif
#include "voxel_grid.glsl"
SHARED_BEGIN

const uint kMaxBrickLevels = 8u;

struct BrickTreeParams {
  GridParams grid;
  uint levels;                   // brick levels 1 … levels (0: the grid only)
  uint offsets[kMaxBrickLevels];  // word offset of level s in brickWords (offsets[0] unused)
};

// Nodes on an axis of n cells at brick level s ≥ 1: a node covers 4^s cells.
SHARED_FN uint bricksPerAxis(uint n, uint s) { return ((n - 1u) >> (2u * s)) + 1u; }

// Levels up to the first whose single node covers the whole grid.
SHARED_FN uint brickLevelCount(uvec4 res) {
  uint s = 1u;
  while (s < kMaxBrickLevels - 1u &&
         (bricksPerAxis(res.x, s) > 1u || bricksPerAxis(res.y, s) > 1u || bricksPerAxis(res.z, s) > 1u))
    s = s + 1u;
  return s;
}

// Index of the word of node (x, y, z) of level s that holds bit `bit` (0 … 63).
SHARED_FN uint brickWordIndex(SHARED_IN(BrickTreeParams) p, uint s, uint x, uint y, uint z, uint bit) {
  uint nx = bricksPerAxis(p.grid.resolution.x, s), ny = bricksPerAxis(p.grid.resolution.y, s);
  return p.offsets[s] + ((z * ny + y) * nx + x) * 2u + (bit >> 5u);
}

// The two words of node (x, y, z) of level s, from the grid (s = 1) or from level s − 1.
SHARED_FN uvec2 brickNodeMask(SHARED_IN(BrickTreeParams) p, uint s, uint x, uint y, uint z BRICK_PARAM) {
  uint m[2];
  m[0] = 0u;
  m[1] = 0u;
  uint W = p.grid.resolution.x, H = p.grid.resolution.y, D = p.grid.resolution.z;
  for (uint bit = 0u; bit < 64u; ++bit) {
    uint i = 4u * x + (bit & 3u), j = 4u * y + ((bit >> 2u) & 3u), k = 4u * z + (bit >> 4u);
    bool set = false;
    if (s == 1u) {
      if (i < W && j < H && k < D) set = (gridWords[columnWordIndex(i, j, depthWord(k), p.grid.resolution)] & depthBit(k)) != 0u;
    } else {
      uint c = s - 1u;
      if (i < bricksPerAxis(W, c) && j < bricksPerAxis(H, c) && k < bricksPerAxis(D, c)) {
        uint w = brickWordIndex(p, c, i, j, k, 0u);
        set = (brickWords[w] | brickWords[w + 1u]) != 0u;
      }
    }
    if (set) m[bit >> 5u] |= 1u << (bit & 31u);
  }
  return uvec2(m[0], m[1]);
}

SHARED_END
