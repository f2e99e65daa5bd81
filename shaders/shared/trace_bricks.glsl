// First hit through the 4³ bricks (brick_tree.glsl): the hierarchical DDA of a 64-tree (Laine & Karras,
// "Efficient Sparse Voxel Octrees", 2010, with 4³ children per node) over dense levels, following
// ray_grid.glsl's definition, so the voxel and distance found are exactly the DDA's (trace_dda.glsl).
//
// The loop keeps the ray parameter t, the level-0 cell c at t and a scale s: the current cube is the
// 4^s-cell cube holding c. Whether it holds geometry is one bit: the grid's at s = 0, else its bit in
// its parent node (level s + 1). Set: refine to s − 1 in place, or report the hit at s = 0. Empty:
// advance t to where the ray leaves the cube (the nearest far plane, by planeT), move every axis to its
// cell at that t (the exit axes to the first cell past their plane, advanceCell; the others by cellAt,
// exact), and go one scale coarser if the ray left the parent cube — the policy of
// trace_hierarchical.glsl. It starts at scale 0: near-field rays start next to a surface.
//
// Exactness: an empty cube holds no set voxel and the ray stays inside it for t ∈ [t, exit), so every
// voxel it visits there is empty; at the exit the cells are the definition's cells at that t, so the
// DDA reaches the same voxel at the same parameter (the same planes through the same planeT).
// Bound: every advance moves some axis across at least one plane, monotonically (≤ W + H + D + 3
// advances), and each advance goes at most one scale coarser, so refinements ≤ advances + levels.
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
#include "ray_grid.glsl"
#include "brick_tree.glsl"
SHARED_BEGIN

SHARED_FN uint bricksMaxSteps(uint w, uint h, uint d, uint levels) { return 2u * (w + h + d + 3u) + levels + 2u; }

// Whether the 4^s cube holding level-0 cell c holds a set voxel (s < p.levels).
SHARED_FN bool brickCubeSet(SHARED_IN(BrickTreeParams) p, uint s, int cx, int cy, int cz BRICK_PARAM) {
  TRACE_FETCHES(1u, 4u);
  if (s == 0u) {
    uint i = columnWordIndex(uint(cx), uint(cy), depthWord(uint(cz)), p.grid.resolution);
    return (gridWords[i] & depthBit(uint(cz))) != 0u;
  }
  uint sh = 2u * s, nsh = sh + 2u;
  uint bit = ((uint(cx) >> sh) & 3u) + 4u * ((uint(cy) >> sh) & 3u) + 16u * ((uint(cz) >> sh) & 3u);
  uint w = brickWordIndex(p, s + 1u, uint(cx) >> nsh, uint(cy) >> nsh, uint(cz) >> nsh, bit);
  return ((brickWords[w] >> (bit & 31u)) & 1u) != 0u;
}

SHARED_FN TraceHit traceBricks(SHARED_IN(BrickTreeParams) p, vec3 origin, vec3 direction, float tmax BRICK_PARAM) {
  GridRay r = prepareGridRay(p.grid, origin, direction, tmax);
  if (r.tHi < 0.0f) return traceMiss(0u);
  int c[3];
  for (int a = 0; a < 3; ++a) c[a] = cellAt(r, a, 0.0f, false);
  float t = 0.0f;
  uint s = 0u;
  // The coarsest cube tested: one below the top node (its bits answer for the cubes of that scale).
  uint top = p.levels > 0u ? p.levels - 1u : 0u;
  uint maxSteps = bricksMaxSteps(uint(r.res[0]), uint(r.res[1]), uint(r.res[2]), p.levels);
  for (uint steps = 1u; steps <= maxSteps; ++steps) {
    if (c[0] < 0 || c[1] < 0 || c[2] < 0 || c[0] >= r.res[0] || c[1] >= r.res[1] || c[2] >= r.res[2])
      return traceMiss(steps);  // leaving the grid
    if (brickCubeSet(p, s, c[0], c[1], c[2] BRICK_ARG)) {
      if (s == 0u) {
        TraceHit h;
        h.hit = 1u;
        h.t = r.tBase + t;
        h.voxel = uvec3(uint(c[0]), uint(c[1]), uint(c[2]));
        h.steps = steps;
        return h;
      }
      s -= 1u;
      TRACE_REFINE();
      continue;
    }
    // Leave the empty cube: its far plane on every moving axis.
    int side = 1 << (2u * s);
    int far[3];
    float tn[3];
    for (int a = 0; a < 3; ++a) {
      int lo = c[a] & ~(side - 1);
      far[a] = r.stepDir[a] > 0 ? min(lo + side, r.res[a]) : lo;
      tn[a] = r.stepDir[a] == 0 ? kTraceInfinity : planeT(r, a, far[a]);
    }
    float tExit = min(tn[0], min(tn[1], tn[2]));
    if (tExit > r.tHi) return traceMiss(steps);
    t = tExit;
    bool up = false;
    uint nsh = 2u * s + 2u;
    for (int a = 0; a < 3; ++a) {
      int n;
      if (tn[a] <= t)
        n = advanceCell(r, a, r.stepDir[a] > 0 ? far[a] : far[a] - 1, t);
      else
        n = s == 0u ? c[a] : cellAt(r, a, t, false);
      up = up || (n >> nsh) != (c[a] >> nsh);
      c[a] = n;
    }
    if (up && s < top) {
      s += 1u;
      TRACE_CLIMB();
    }
  }
  return traceMiss(maxSteps + 1u);  // unreachable by the bound above
}

SHARED_END
