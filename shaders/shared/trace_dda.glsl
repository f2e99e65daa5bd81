// 3D DDA over level 0 of the pyramid (the grid; pyramidFromLevel: a coarser level) — Amanatides & Woo, "A Fast Voxel Traversal
// Algorithm for Ray Tracing", Eurographics 1987: step to the neighbour across
// the nearest cell boundary, one voxel at a time. It is the correctness oracle
// for the hierarchical tracer, so it follows ray_grid.glsl's definition
// literally: boundary parameters come from planeT() (never accumulated as
// tMax += tDelta, which drifts), and every axis whose boundary is crossed at the
// same t steps at once (a ray through an edge or corner moves diagonally).
// At most W + H + D + 3 iterations: each one advances some axis monotonically.
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
#include "or_mip.glsl"
#include "ray_grid.glsl"
SHARED_BEGIN

SHARED_FN bool voxelSet(SHARED_IN(PyramidParams) p, int x, int y, int z PYRAMID_PARAM) {
  uint i = p.levelOffsets[0] + columnWordIndex(uint(x), uint(y), depthWord(uint(z)), p.grid.resolution);
  TRACE_FETCHES(1u, 4u);
  return (pyramidWords[i] & depthBit(uint(z))) != 0u;
}

SHARED_FN TraceHit traceDda(SHARED_IN(PyramidParams) p, vec3 origin, vec3 direction, float tmax PYRAMID_PARAM) {
  GridRay r = prepareGridRay(p.grid, origin, direction, tmax);
  if (r.tHi < 0.0f) return traceMiss(0u);
  int c[3];
  for (int a = 0; a < 3; ++a) c[a] = cellAt(r, a, 0.0f, false);
  float t = 0.0f;
  uint maxSteps = uint(r.res[0] + r.res[1] + r.res[2]) + 3u;
  for (uint steps = 1u; steps <= maxSteps; ++steps) {
    if (c[0] < 0 || c[1] < 0 || c[2] < 0 || c[0] >= r.res[0] || c[1] >= r.res[1] || c[2] >= r.res[2])
      return traceMiss(steps);  // leaving the grid
    if (voxelSet(p, c[0], c[1], c[2] PYRAMID_ARG)) {
      TraceHit h;
      h.hit = 1u;
      h.t = r.tBase + t;
      h.voxel = uvec3(uint(c[0]), uint(c[1]), uint(c[2]));
      h.steps = steps;
      return h;
    }
    float tn[3];
    for (int a = 0; a < 3; ++a)
      tn[a] = r.stepDir[a] == 0 ? kTraceInfinity : planeT(r, a, r.stepDir[a] > 0 ? c[a] + 1 : c[a]);
    float tNext = min(tn[0], min(tn[1], tn[2]));
    if (tNext > r.tHi) return traceMiss(steps);
    t = tNext;
    // Every axis whose plane is crossed at t steps (planes that round to the
    // same parameter are crossed together): advanceCell.
    for (int a = 0; a < 3; ++a)
      if (tn[a] <= t) c[a] = advanceCell(r, a, c[a], t);
  }
  return traceMiss(maxSteps + 1u);
}

SHARED_END
