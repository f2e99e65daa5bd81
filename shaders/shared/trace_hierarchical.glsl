// Hierarchical first hit and two-point visibility over the OR-mip pyramid —
// Thiedemann et al., "Voxel-based Global Illumination", I3D 2011, §4.1–4.2
// (refining Forest et al. 2009 by dropping the octree). Start at the coarsest
// level; intersect the ray with the current column's box; build the mask of
// the depth cells the ray crosses inside the column and AND it with the stored
// column. Empty: advance to the column exit and go one level coarser. Not
// empty: one level finer; at level 0 the lowest set bit of the AND (highest
// when the ray runs against the depth axis) is the first hit.
//
// Differences from the paper, for exactness against the DDA oracle: the loop
// tracks the integer level-0 cell (x, y) and the ray parameter t rather than a
// projected position, and every cell and depth range comes from the shared
// definition in ray_grid.glsl, so the voxel found is exactly the one the DDA
// finds. The depth mask is built per 32-bit word of the column and only over
// the words the ray touches (never shifting by 32). After an advance it goes
// coarser only if the exit left the parent column (the paper always does).
// Before refining a non-empty column it skips along the ray to the first
// depth cell that can hold geometry there (the AND's first bit): rays that run
// along the depth axis skip most of their refinements. It starts at level 0
// instead of the top (see below).
//
// Iteration bound: every advance moves x or y across at least one level-0
// plane (its column's exit plane is crossed at exactly the new t, so cellAt
// passes it), and x, y move monotonically (skips only move forward inside the
// current column), so there are at most W + H + 2 advances; between two
// advances there are at most `levels` refinements and one coarsening. kHierarchicalMaxSteps(W, H, levels) is that bound; the
// loop also stops there, and tests check it is never reached.
//
// The pyramid's words: a C++ pointer argument, or a GLSL buffer named
// pyramidWords declared by the including shader (PYRAMID_PARAM / PYRAMID_ARG).
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
#include "or_mip.glsl"
#include "ray_grid.glsl"
SHARED_BEGIN

SHARED_FN uint hierarchicalMaxSteps(uint w, uint h, uint levels) { return (w + h + 3u) * (levels + 2u) + levels; }

// The first set bit among depth cells k0 … k1 (k0 ≤ k1) of one column of one
// level, searched upwards (forward) or downwards; −1 if none.
SHARED_FN int firstSetDepth(uint index0, uint k0, uint k1, bool forward PYRAMID_PARAM) {
  uint w0 = k0 >> 5u, w1 = k1 >> 5u;
  uint n = w1 - w0;
  for (uint i = 0u; i <= n; ++i) {
    uint w = forward ? w0 + i : w1 - i;
    uint lo = w == w0 ? (k0 & 31u) : 0u;
    uint hi = w == w1 ? (k1 & 31u) : 31u;
    // Word w of a column sits at slab w/4, component w%4 (voxel_grid.glsl); the
    // caller passes the index of word 0 and the slab stride in index0's level.
    uint m = pyramidWords[index0 + w] & bitRange(lo, hi);
    TRACE_FETCHES(1u, 4u);
    if (m != 0u) return int(w * 32u) + (forward ? findLSB(m) : findMSB(m));
  }
  return -1;
}

SHARED_FN TraceHit traceHierarchical(SHARED_IN(PyramidParams) p, vec3 origin, vec3 direction, float tmax PYRAMID_PARAM) {
  GridRay r = prepareGridRay(p.grid, origin, direction, tmax);
  if (r.tHi < 0.0f) return traceMiss(0u);
  int cx = cellAt(r, 0, 0.0f, false);
  int cy = cellAt(r, 1, 0.0f, false);
  int kA = cellAt(r, 2, 0.0f, false);  // depth cell at t (kept up to date on every advance)
  float t = 0.0f;
  // Start at level 0 and let empty columns carry the ray up (the paper starts
  // at the top). Near-field rays start next to a surface, where every coarse
  // column is non-empty: starting at the top costs `levels` refinements per ray
  // for nothing (measured on Sibenik 256³: 5.1 vs 4.2 Mrays/s, docs/BENCHMARKS.md).
  uint level = 0u;
  uint maxSteps = hierarchicalMaxSteps(uint(r.res[0]), uint(r.res[1]), p.levels);
  int depth = r.res[2];
  bool forward = r.stepDir[2] >= 0;
  for (uint steps = 1u; steps <= maxSteps; ++steps) {
    if (cx < 0 || cy < 0 || cx >= r.res[0] || cy >= r.res[1]) return traceMiss(steps);  // leaving the grid
    // This level's column and its extent in level-0 cells.
    int colX = cx >> level, colY = cy >> level;
    int x0 = colX << level, y0 = colY << level;
    int x1 = min(x0 + (1 << level), r.res[0]), y1 = min(y0 + (1 << level), r.res[1]);
    float tx = r.stepDir[0] > 0 ? planeT(r, 0, x1) : (r.stepDir[0] < 0 ? planeT(r, 0, x0) : kTraceInfinity);
    float ty = r.stepDir[1] > 0 ? planeT(r, 1, y1) : (r.stepDir[1] < 0 ? planeT(r, 1, y0) : kTraceInfinity);
    float tCol = min(tx, ty);
    bool ends = tCol > r.tHi;  // the ray ends inside this column (the end point counts)
    int kB = cellAt(r, 2, ends ? r.tHi : tCol, !ends);
    int k0 = max(min(kA, kB), 0), k1 = min(max(kA, kB), depth - 1);
    if (k0 <= k1) {
      uint levelW = ((uint(r.res[0]) - 1u) >> level) + 1u;
      uint levelH = ((uint(r.res[1]) - 1u) >> level) + 1u;
      // Word w of a column sits at slab w/4, component w%4 (voxel_grid.glsl):
      // search slab by slab, each a contiguous run of 4 words.
      uint slabStride = levelW * levelH * 4u;
      uint base = p.levelOffsets[level] + (uint(colY) * levelW + uint(colX)) * 4u;
      int found = -1;
      uint s0 = uint(k0) >> 7u, s1 = uint(k1) >> 7u;
      for (uint i = 0u; i <= s1 - s0 && found < 0; ++i) {
        uint s = forward ? s0 + i : s1 - i;
        uint lo = max(uint(k0), s * 128u) - s * 128u;
        uint hi = min(uint(k1), s * 128u + 127u) - s * 128u;
        int f = firstSetDepth(base + s * slabStride, lo, hi, forward PYRAMID_ARG);
        if (f >= 0) found = int(s * 128u) + f;
      }
      if (found >= 0) {
        if (level == 0u) {
          TraceHit h;
          h.hit = 1u;
          h.t = r.tBase + max(t, cellEntryT(r, 2, found));
          h.voxel = uvec3(uint(cx), uint(cy), uint(found));
          h.steps = steps;
          return h;
        }
        // A coarse column only says "maybe": refine. Nothing lies on the ray in
        // this column before depth cell `found`, so first skip to where the ray
        // enters it (still inside the column: found ≤ kB, entered before tCol).
        float ts = cellEntryT(r, 2, found);
        if (ts > t) {
          t = ts;
          cx = cellAt(r, 0, t, false);
          cy = cellAt(r, 1, t, false);
          kA = cellAt(r, 2, t, false);
        }
        level -= 1u;
        TRACE_REFINE();
        continue;
      }
    }
    if (ends) return traceMiss(steps);
    // Advance to the column exit. The exit axis jumps to the first cell past the
    // column's plane; the other axis and the depth come from the definition at
    // t (cheap guesses, then exact); stepping cell by cell through a coarse
    // column would cost what the hierarchy saves.
    t = tCol;
    int nx = tx == t ? advanceCell(r, 0, r.stepDir[0] > 0 ? x1 : x0 - 1, t) : (level == 0u ? cx : cellAt(r, 0, t, false));
    int ny = ty == t ? advanceCell(r, 1, r.stepDir[1] > 0 ? y1 : y0 - 1, t) : (level == 0u ? cy : cellAt(r, 1, t, false));
    kA = advanceCell(r, 2, kB, t);
    uint up = level + 1u;
    if (up < p.levels && ((nx >> up) != (cx >> up) || (ny >> up) != (cy >> up))) {
      level = up;
      TRACE_CLIMB();
    }
    cx = nx;
    cy = ny;
  }
  return traceMiss(maxSteps + 1u);  // unreachable by the bound above
}

// Two-point visibility (§4.1): the same loop ending at b. Both end points are
// included, so callers offset them off their surfaces.
SHARED_FN bool visibleHierarchical(SHARED_IN(PyramidParams) p, vec3 a, vec3 b PYRAMID_PARAM) {
  return traceHierarchical(p, a, b - a, 1.0f PYRAMID_ARG).hit == 0u;
}

SHARED_END
