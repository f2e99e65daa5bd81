// Fixed-step ray marching, as the AVG paper traces its visibility grid
// (Bashford-Rogers et al., "Approximate Visibility Grids for Interactive
// Indirect Illumination"): sample the grid at t = 0, s, 2s, … and report the
// first occupied sample. It can step over thin or corner-touched voxels and
// reports the sample's t, not the voxel entry; the benchmark measures what that
// costs against the DDA and Embree. Samples are capped at kMaxMarchSteps.
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
#include "trace_dda.glsl"
SHARED_BEGIN

const uint kMaxMarchSteps = 1048576u;

SHARED_FN TraceHit traceMarch(SHARED_IN(PyramidParams) p, vec3 origin, vec3 direction, float tmax, float stepLength PYRAMID_PARAM) {
  GridRay r = prepareGridRay(p.grid, origin, direction, tmax);
  if (r.tHi < 0.0f || !(stepLength > 0.0f)) return traceMiss(0u);
  uint n = uint(min(r.tHi / stepLength, float(kMaxMarchSteps - 1u))) + 1u;
  for (uint i = 0u; i < n; ++i) {
    SHARED_PRECISE float t = float(i) * stepLength;
    int c[3];
    for (int a = 0; a < 3; ++a) {
      SHARED_PRECISE float q = r.o[a] + t * r.d[a];
      c[a] = min(int(max(q, 0.0f)), r.res[a] - 1);  // floor for q ≥ 0, without a libm call
    }
    if (voxelSet(p, c[0], c[1], c[2] PYRAMID_ARG)) {
      TraceHit h;
      h.hit = 1u;
      h.t = r.tBase + t;
      h.voxel = uvec3(uint(c[0]), uint(c[1]), uint(c[2]));
      h.steps = i + 1u;
      return h;
    }
  }
  return traceMiss(n);
}

SHARED_END
