// A ray in grid space and the one definition of "the voxels a ray visits" that
// every voxel tracer (hierarchical, dda, march) follows, so they can be compared
// exactly (VGI §4; DDA after Amanatides & Woo 1987).
//
// Definition. The prepared ray has a grid-space origin o (clamped into the
// closed grid box), a direction d per unit of world distance, and a parameter
// range t ∈ [0, tHi] (t is world distance from the grid entry). On axis a the
// integer plane p is crossed at T_a(p) = (p − o_a)·(1/d_a), always evaluated by
// planeT() below. The cell on axis a at t is
//   d_a > 0: max{ p : T_a(p) ≤ t }      d_a < 0: min{ p : T_a(p+1) ≤ t }
//   d_a = 0: floor(o_a) (the upper face belongs to the last cell)
// and the voxel at t is the triple of those cells. The ray visits the voxels
// at t ∈ [0, tHi] that lie in the grid; its first hit is the visited voxel with
// the smallest entry parameter. Ties (a ray through an edge or a corner) are
// therefore decided by the definition, not by a tracer's loop order: all axes
// whose planes are crossed at the same t step together. Because every tracer
// evaluates T through planeT() on the same prepared ray, they agree bit for bit.
//
// Numerical traps handled here: ±0 and tiny direction components (1/d would be
// ±inf and 0·inf = NaN) are set to exactly 0; origins far outside the grid are
// rebased to the grid entry so T keeps its precision; a clamped origin makes
// "the cell left the grid" mean "the ray is leaving", so tracers may stop there.
// The prepared ray is computed with `precise` arithmetic in GLSL (no fused
// multiply-add) so llvmpipe and the C++ build (compiled with -ffp-contract=off)
// produce the same bits.
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
#include "voxel_grid.glsl"
SHARED_BEGIN

const float kTraceInfinity = 3.0e38f;
// Direction components below this (grid cells per world unit) count as 0: their
// planes would be crossed beyond any finite ray anyway.
const float kTinyDirection = 1.0e-20f;

// Arrays rather than vectors: GLM's vec[i] is a switch, an array index is not.
struct GridRay {
  float o[3];       // grid-space origin, clamped into [0, W] × [0, H] × [0, D]
  float d[3];       // grid-space direction per unit world distance (tiny parts = 0)
  float inv[3];     // 1 / d per axis, 0 where d is 0
  int stepDir[3];   // sign of d: +1, −1 or 0
  int res[3];       // W, H, D
  float tBase;    // world distance from the ray's origin to o
  float tHi;      // last parameter inside the grid and the ray; < 0: no voxel visited
};

// Finite, neither NaN nor ±inf.
SHARED_FN bool isFiniteFloat(float x) { return (floatBitsToUint(x) & 0x7f800000u) != 0x7f800000u; }

SHARED_FN GridRay prepareGridRay(SHARED_IN(GridParams) g, vec3 origin, vec3 direction, float tmax) {
  GridRay r;
  r.tBase = 0.0f;
  r.tHi = -1.0f;
  vec4 axes[3];
  axes[0] = g.axisX;
  axes[1] = g.axisY;
  axes[2] = g.axisZ;
  for (int a = 0; a < 3; ++a) {
    r.res[a] = int(g.resolution[a]);
    r.o[a] = 0.0f;
    r.d[a] = 0.0f;
    r.inv[a] = 0.0f;
    r.stepDir[a] = 0;
  }
  bool finiteInput = isFiniteFloat(origin.x) && isFiniteFloat(origin.y) && isFiniteFloat(origin.z) &&
                     isFiniteFloat(direction.x) && isFiniteFloat(direction.y) && isFiniteFloat(direction.z) &&
                     !(tmax != tmax) && tmax >= 0.0f;
  if (!finiteInput) return r;
  SHARED_PRECISE vec3 rel = origin - vec3(g.origin.x, g.origin.y, g.origin.z);
  float q[3];
  SHARED_PRECISE float tEnter = 0.0f;
  SHARED_PRECISE float tExit = min(tmax, kTraceInfinity);
  for (int a = 0; a < 3; ++a) {
    SHARED_PRECISE float qa = rel.x * axes[a].x;
    qa = qa + rel.y * axes[a].y;
    qa = qa + rel.z * axes[a].z;
    qa = qa * axes[a].w;
    q[a] = qa;
    SHARED_PRECISE float da = direction.x * axes[a].x;
    da = da + direction.y * axes[a].y;
    da = da + direction.z * axes[a].z;
    da = da * axes[a].w;
    float lo = 0.0f, hi = float(r.res[a]);
    if (abs(da) < kTinyDirection) {
      if (qa < lo || qa > hi) return r;  // parallel to this slab and outside it
    } else {
      r.d[a] = da;
      r.stepDir[a] = da > 0.0f ? 1 : -1;
      r.inv[a] = 1.0f / da;
      SHARED_PRECISE float t0 = ((da > 0.0f ? lo : hi) - qa) * r.inv[a];
      SHARED_PRECISE float t1 = ((da > 0.0f ? hi : lo) - qa) * r.inv[a];
      tEnter = max(tEnter, t0);
      tExit = min(tExit, t1);
    }
  }
  if (r.stepDir[0] == 0 && r.stepDir[1] == 0 && r.stepDir[2] == 0) return r;  // no direction
  if (!(tEnter <= tExit)) return r;
  r.tBase = tEnter;
  r.tHi = tExit - tEnter;
  for (int a = 0; a < 3; ++a) {
    SHARED_PRECISE float oa = q[a] + tEnter * r.d[a];
    r.o[a] = clamp(oa, 0.0f, float(r.res[a]));
  }
  return r;
}

// The parameter at which the ray crosses integer plane p of axis a (d_a ≠ 0).
SHARED_FN float planeT(SHARED_IN(GridRay) r, int a, int p) {
  SHARED_PRECISE float t = (float(p) - r.o[a]) * r.inv[a];
  return t;
}

// The cell on axis a at parameter t (the definition above), clamped to
// [−1, res]: −1 and res are "outside". With `before` set, the cell just before
// t (planes crossed exactly at t do not count yet): the last cell of a column
// that the ray leaves at t. The guess from the position is off by at most a
// cell or two; the loops make the result exact and are bounded by the clamp.
SHARED_FN int cellAt(SHARED_IN(GridRay) r, int a, float t, bool before) {
  int n = r.res[a];
  if (r.stepDir[a] == 0) return min(int(r.o[a]), n - 1);  // o ≥ 0: truncation is floor
  SHARED_PRECISE float pos = r.o[a] + t * r.d[a];
  // Truncation, not floor: only a guess (the loops fix it), and floorf is a
  // library call on baseline x86-64.
  int c = int(clamp(pos, -1.0f, float(n)));
  if (r.stepDir[a] > 0) {
    // max{p : T(p) ≤ t}   (before: T(p) < t)
    while (c < n && (before ? planeT(r, a, c + 1) < t : planeT(r, a, c + 1) <= t)) ++c;
    while (c > -1 && (before ? planeT(r, a, c) >= t : planeT(r, a, c) > t)) --c;
  } else {
    // min{p : T(p+1) ≤ t}   (before: T(p+1) < t)
    while (c > -1 && (before ? planeT(r, a, c) < t : planeT(r, a, c) <= t)) --c;
    while (c < n && (before ? planeT(r, a, c + 1) >= t : planeT(r, a, c + 1) > t)) ++c;
  }
  return c;
}

// Moves cell c of axis a (the cell at an earlier parameter) to the cell at t:
// exact by monotonicity, and cheaper than cellAt when t moved little.
SHARED_FN int advanceCell(SHARED_IN(GridRay) r, int a, int c, float t) {
  int s = r.stepDir[a];
  if (s > 0) {
    while (c < r.res[a] && planeT(r, a, c + 1) <= t) ++c;
  } else if (s < 0) {
    while (c > -1 && planeT(r, a, c) <= t) --c;
  }
  return c;
}

// The parameter at which the ray enters cell c of axis a (0 for d_a = 0).
SHARED_FN float cellEntryT(SHARED_IN(GridRay) r, int a, int c) {
  if (r.stepDir[a] == 0) return 0.0f;
  return planeT(r, a, r.stepDir[a] > 0 ? c : c + 1);
}

// The world distance from the ray's origin at which it leaves voxel v (the
// first plane of v's far faces that it crosses): where a trace resumes past v.
SHARED_FN float voxelExitT(SHARED_IN(GridRay) r, uvec3 v) {
  uint c[3];
  c[0] = v.x;
  c[1] = v.y;
  c[2] = v.z;
  float t = kTraceInfinity;
  for (int a = 0; a < 3; ++a)
    if (r.stepDir[a] != 0) t = min(t, planeT(r, a, r.stepDir[a] > 0 ? int(c[a]) + 1 : int(c[a])));
  return r.tBase + t;
}

// What a tracer returns. t is world distance from the ray's origin to where the
// ray enters the hit voxel (or its start, if it starts inside).
struct TraceHit {
  uint hit;    // 1 or 0
  float t;
  uvec3 voxel;
  uint steps;  // loop iterations (for the bound checks and profiling)
};

SHARED_FN TraceHit traceMiss(uint steps) {
  TraceHit h;
  h.hit = 0u;
  h.t = 0.0f;
  h.voxel = uvec3(0u);
  h.steps = steps;
  return h;
}

SHARED_END
