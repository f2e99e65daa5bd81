// 3D DDA over level 0 of the grid — Amanatides & Woo, "A Fast Voxel Traversal
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
#include "or_mip.glsl"
#include "ray_grid.glsl"
#endif
SHARED_BEGIN

SHARED_FN bool voxelSet(PyramidParams p, int x, int y, int z PYRAMID_PARAM) {
  uint i = columnWordIndex(uint(x), uint(y), depthWord(uint(z)), p.grid.resolution);
  return (pyramidWords[i] & depthBit(uint(z))) != 0u;
}

SHARED_FN TraceHit traceDda(PyramidParams p, vec3 origin, vec3 direction, float tmax PYRAMID_PARAM) {
  GridRay r = prepareGridRay(p.grid, origin, direction, tmax);
  if (r.tHi < 0.0f) return traceMiss(0u);
  ivec3 c = ivec3(cellAt(r, 0, 0.0f, false), cellAt(r, 1, 0.0f, false), cellAt(r, 2, 0.0f, false));
  float t = 0.0f;
  uint maxSteps = uint(r.res.x + r.res.y + r.res.z) + 3u;
  for (uint steps = 1u; steps <= maxSteps; ++steps) {
    if (c.x < 0 || c.y < 0 || c.z < 0 || c.x >= r.res.x || c.y >= r.res.y || c.z >= r.res.z)
      return traceMiss(steps);  // leaving the grid
    if (voxelSet(p, c.x, c.y, c.z PYRAMID_ARG)) {
      TraceHit h;
      h.hit = 1u;
      h.t = r.tBase + t;
      h.voxel = uvec3(c);
      h.steps = steps;
      return h;
    }
    vec3 tn;
    for (int a = 0; a < 3; ++a)
      tn[a] = r.stepDir[a] == 0 ? kTraceInfinity : planeT(r, a, r.stepDir[a] > 0 ? c[a] + 1 : c[a]);
    float tNext = min(tn.x, min(tn.y, tn.z));
    if (tNext > r.tHi) return traceMiss(steps);
    t = tNext;
    for (int a = 0; a < 3; ++a) {
      if (r.stepDir[a] == 0 || tn[a] > t) continue;
      c[a] += r.stepDir[a];
      // Planes that round to the same parameter are crossed together.
      while (c[a] >= 0 && c[a] < r.res[a] && planeT(r, a, r.stepDir[a] > 0 ? c[a] + 1 : c[a]) <= t)
        c[a] += r.stepDir[a];
    }
  }
  return traceMiss(maxSteps + 1u);
}

SHARED_END
