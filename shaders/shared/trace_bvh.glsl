// Exact first hit and any-hit visibility on the scene's triangles through a
// binary BVH — the same-device exact counterpart of the voxel tracers.
//
// Layout (Aila & Laine, "Understanding the Efficiency of Ray Traversal on
// GPUs", HPG 2009: the children's boxes stored in the parent, so one node
// fetch tests them all), W = 2 children per node, or 4 (a wide BVH, as
// Embree's own BVH4 and Wald et al. 2008's, fewer nodes per ray): node i is 2W
// vec4 in `bvhNodes` from 2W·i,
//   [2W·i + 2c]     child c's box min, w = its ref (uint bits)
//   [2W·i + 2c + 1] child c's box max, w = its triangle count (uint bits; 0: an inner node);
// an inner child's ref is a node index, a leaf's the first of its `count`
// triangles in `bvhTris` (three vec4 each: the corners, w of the first = the
// triangle's index in the flattened scene). An empty child has min > max.
// Node 0 is the root. The tree is built by Embree's BVH builder (SAH) on the
// CPU (traverse/gpu_bvh.h), which leaves out triangles of zero area (their
// edge functions are rounding noise: a hit on one would be at a random t).
//
// Ray–triangle: the watertight test of Woop, Benthin and Wald, "Watertight
// Ray/Triangle Intersection", JCGT 2013: shear into the ray's frame (kz the
// dominant axis), 2D edge functions U, V, W recomputed in double when one is
// exactly 0, so a ray through an edge or a vertex hits at least one of the
// triangles that share it. A hit needs 0 < t <= tmax, as Embree's robust
// mode: a ray starting exactly on a surface does not hit it at t = 0; a ray
// in a triangle's plane does not hit it.
// Ray–box: slabs with the far distance scaled by 1 + 2γ₃ (Ize, "Robust BVH
// Ray Traversal", JCGT 2013), so no box that holds a hit is culled by
// rounding, and against the best hit so far with a slack (kBoxSlack).
//
// The arrays: C++ pointer arguments, or GLSL buffers named bvhNodes and
// bvhTris declared by the including shader (BVH_PARAM / BVH_ARG).
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
#include "ray_grid.glsl"
SHARED_BEGIN

// The traversal stack: each node pops one entry and pushes at most width of
// them, so a tree of depth d needs (width − 1)·d + 1 entries; the builder
// limits the depth to bvhMaxDepth(width) (60 for a binary tree, 20 for a
// 4-wide one), within kBvhStackSize.
const int kBvhStackSize = 64;
const uint kBvhMaxDepth = 60u;
const uint kBvhMaxWidth = 4u;
// The width the scene resource builds (illum/resources/gpu_bvh) and a program traces unless it is
// compiled with another BVH_WIDTH (traverse/gpu_bvh.h, addBvhDefine): one constant for both sides.
const uint kBvhDefaultWidth = 2u;
SHARED_FN uint bvhMaxDepth(uint width) {
  return min(kBvhMaxDepth, (uint(kBvhStackSize) - 4u) / (width - 1u));
}

struct BvhHit {
  uint hit;       // 1 or 0
  float t;        // world distance along the unit direction to the surface
  uint triangle;  // index in the flattened scene
  float u, v;     // barycentrics of corners 1 and 2
  uint steps;     // nodes visited (profiling)
};

// The ray in the triangles' sheared frame (Woop et al. §3).
struct WatertightRay {
  int kx, ky, kz;
  float sx, sy, sz;
};

SHARED_FN WatertightRay watertightRay(vec3 dir) {
  WatertightRay w;
  vec3 a = abs(dir);
  w.kz = a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
  w.kx = w.kz == 2 ? 0 : w.kz + 1;
  w.ky = w.kx == 2 ? 0 : w.kx + 1;
  if (dir[w.kz] < 0.0f) {
    int k = w.kx;
    w.kx = w.ky;
    w.ky = k;
  }
  w.sx = dir[w.kx] / dir[w.kz];
  w.sy = dir[w.ky] / dir[w.kz];
  w.sz = 1.0f / dir[w.kz];
  return w;
}

// Triangle (p0, p1, p2) against the ray from `origin`; a hit nearer than
// `tBest` (and > 0) returns hit = 1 with t, u, v.
SHARED_FN BvhHit intersectWatertight(SHARED_IN(WatertightRay) w, vec3 origin, vec3 p0, vec3 p1, vec3 p2,
                                     float tBest) {
  BvhHit h;
  h.hit = 0u;
  h.t = tBest;
  h.triangle = 0u;
  h.u = 0.0f;
  h.v = 0.0f;
  h.steps = 0u;
  SHARED_PRECISE vec3 a = p0 - origin;
  SHARED_PRECISE vec3 b = p1 - origin;
  SHARED_PRECISE vec3 c = p2 - origin;
  SHARED_PRECISE float ax = a[w.kx] - w.sx * a[w.kz];
  SHARED_PRECISE float ay = a[w.ky] - w.sy * a[w.kz];
  SHARED_PRECISE float bx = b[w.kx] - w.sx * b[w.kz];
  SHARED_PRECISE float by = b[w.ky] - w.sy * b[w.kz];
  SHARED_PRECISE float cx = c[w.kx] - w.sx * c[w.kz];
  SHARED_PRECISE float cy = c[w.ky] - w.sy * c[w.kz];
  SHARED_PRECISE float u = cx * by - cy * bx;
  SHARED_PRECISE float v = ax * cy - ay * cx;
  SHARED_PRECISE float e = bx * ay - by * ax;
  if (u == 0.0f || v == 0.0f || e == 0.0f) {
    // On an edge in float: decide in double (exact for these products), so
    // that the triangles sharing the edge agree on which side the ray passes.
    u = float(double(cx) * double(by) - double(cy) * double(bx));
    v = float(double(ax) * double(cy) - double(ay) * double(cx));
    e = float(double(bx) * double(ay) - double(by) * double(ax));
  }
  if ((u < 0.0f || v < 0.0f || e < 0.0f) && (u > 0.0f || v > 0.0f || e > 0.0f)) return h;
  SHARED_PRECISE float det = u + v + e;
  // A ray in the triangle's plane (or within ~1e-6 rad of it): the edge
  // functions are all rounding noise, and so would be t. No hit, as Embree.
  SHARED_PRECISE float scale =
      abs(cx * by) + abs(cy * bx) + abs(ax * cy) + abs(ay * cx) + abs(bx * ay) + abs(by * ax);
  if (!(abs(det) > 1.0e-6f * scale)) return h;
  SHARED_PRECISE float az = w.sz * a[w.kz];
  SHARED_PRECISE float bz = w.sz * b[w.kz];
  SHARED_PRECISE float cz = w.sz * c[w.kz];
  SHARED_PRECISE float tScaled = u * az + v * bz + e * cz;
  SHARED_PRECISE float absDet = abs(det);
  SHARED_PRECISE float tSigned = det < 0.0f ? -tScaled : tScaled;
  if (!(tSigned > 0.0f)) return h;
  // Compared as a distance (not T against tBest·det): a ray whose tmax is its
  // own hit distance hits, whatever the rounding.
  SHARED_PRECISE float t = tSigned / absDet;
  if (!(t > 0.0f) || t > tBest) return h;
  h.hit = 1u;
  h.t = t;
  h.u = v / det;
  h.v = e / det;
  return h;
}

// The ray's parameter interval inside the slab [lo, hi] of one axis; a ray
// parallel to it (inv = 0) is inside for every t or for none — also when it
// runs exactly in a face's plane, where 1/d arithmetic would give 0·∞.
struct SlabSpan {
  float tIn, tOut;
};
SHARED_FN SlabSpan slabSpan(float o, float lo, float hi, float inv) {
  SlabSpan s;
  if (inv == 0.0f) {
    bool inside = o >= lo && o <= hi;
    s.tIn = inside ? -kTraceInfinity : kTraceInfinity;
    s.tOut = inside ? kTraceInfinity : -kTraceInfinity;
    return s;
  }
  SHARED_PRECISE float t0 = (lo - o) * inv;
  SHARED_PRECISE float t1 = (hi - o) * inv;
  s.tIn = min(t0, t1);
  s.tOut = max(t0, t1);
  return s;
}

// A box is entered before the current best hit if its entry is at most
// kBoxSlack times that hit's distance: the triangle test computes its t in
// its own way, with its own rounding, and a triangle lies on its box's faces,
// so a ray whose tmax is its own hit distance must not lose the box to 1 ulp.
const float kBoxSlack = 1.001f;

// Entry distance of the ray into the box [lo, hi] (0 if it starts inside),
// or +∞ if the slabs do not overlap in front of the origin; invDir is 0 where
// the direction is (see traceBvh).
SHARED_FN float boxEntry(vec3 origin, vec3 invDir, vec4 lo, vec4 hi) {
  SlabSpan x = slabSpan(origin.x, lo.x, hi.x, invDir.x);
  SlabSpan y = slabSpan(origin.y, lo.y, hi.y, invDir.y);
  SlabSpan z = slabSpan(origin.z, lo.z, hi.z, invDir.z);
  float tNear = max(max(x.tIn, y.tIn), max(z.tIn, 0.0f));
  float tExit = min(min(x.tOut, y.tOut), z.tOut);
  // 1 + 2γ₃ (γ₃ = 3ε / (1 − 3ε), ε = 2⁻²⁴): the exit may only be rounded outwards.
  SHARED_PRECISE float tExitSafe = tExit * 1.00000036f;
  bool empty = lo.x > hi.x;
  return (empty || tNear > tExitSafe) ? kTraceInfinity * 2.0f : tNear;
}

SHARED_FN BvhHit bvhMiss(uint steps) {
  BvhHit h;
  h.hit = 0u;
  h.t = 0.0f;
  h.triangle = 0u;
  h.u = 0.0f;
  h.v = 0.0f;
  h.steps = steps;
  return h;
}

// Whether a ray can be traced: a finite origin and direction, a non-zero
// direction, tmax ≥ 0 (not NaN).
SHARED_FN bool bvhRayValid(vec3 origin, vec3 dir, float tmax) {
  return isFiniteFloat(origin.x) && isFiniteFloat(origin.y) && isFiniteFloat(origin.z) &&
         isFiniteFloat(dir.x) && isFiniteFloat(dir.y) && isFiniteFloat(dir.z) && !(tmax != tmax) &&
         tmax >= 0.0f && (dir.x != 0.0f || dir.y != 0.0f || dir.z != 0.0f);
}

// 1/dir for the slabs, 0 for components too small to invert finitely (the
// slabs treat the ray as parallel there).
SHARED_FN vec3 bvhInvDir(vec3 dir) {
  return vec3(abs(dir.x) < 1e-30f ? 0.0f : 1.0f / dir.x, abs(dir.y) < 1e-30f ? 0.0f : 1.0f / dir.y,
              abs(dir.z) < 1e-30f ? 0.0f : 1.0f / dir.z);
}

// The triangles [ref, ref + count) of a leaf against the ray; returns `best`
// replaced by a nearer hit (with anyHit: stops at the first).
SHARED_FN BvhHit intersectLeaf(SHARED_IN(WatertightRay) w, vec3 origin, uint ref, uint count, BvhHit best,
                               bool anyHit BVH_PARAM) {
  for (uint i = ref; i < ref + count; ++i) {
    vec4 q0 = bvhTris[3u * i];
    vec4 q1 = bvhTris[3u * i + 1u];
    vec4 q2 = bvhTris[3u * i + 2u];
    TRACE_FETCHES(3u, 48u);
    BvhHit h = intersectWatertight(w, origin, vec3(q0.x, q0.y, q0.z), vec3(q1.x, q1.y, q1.z),
                                   vec3(q2.x, q2.y, q2.z), best.t);
    if (h.hit != 0u) {
      best = h;
      best.triangle = floatBitsToUint(q0.w);
      if (anyHit) return best;
    }
  }
  return best;
}

// The binary BVH's traversal, written for two children (the generic loop
// below, with its arrays indexed at run time, ran 28 % slower on llvmpipe).
SHARED_FN BvhHit traceBvh2(vec3 origin, vec3 dir, float tmax, bool anyHit BVH_PARAM) {
  if (!bvhRayValid(origin, dir, tmax)) return bvhMiss(0u);
  WatertightRay w = watertightRay(dir);
  vec3 invDir = bvhInvDir(dir);
  BvhHit best = bvhMiss(0u);
  // Finite, so that a missed box (entry +∞) stays beyond it, slack and all.
  best.t = min(tmax, kTraceInfinity);
  uint stack[kBvhStackSize];
  int sp = 0;
  stack[sp] = 0u;
  sp = sp + 1;
  uint steps = 0u;
  while (sp > 0) {
    sp = sp - 1;
    uint node = stack[sp];
    steps = steps + 1u;
    uint base = node * 4u;
    vec4 lo0 = bvhNodes[base];
    vec4 hi0 = bvhNodes[base + 1u];
    vec4 lo1 = bvhNodes[base + 2u];
    vec4 hi1 = bvhNodes[base + 3u];
    TRACE_FETCHES(4u, 64u);
    float e0 = boxEntry(origin, invDir, lo0, hi0);
    float e1 = boxEntry(origin, invDir, lo1, hi1);
    bool in0 = e0 <= best.t * kBoxSlack, in1 = e1 <= best.t * kBoxSlack;
    uint inner[2];
    float innerEntry[2];
    int innerCount = 0;
    for (int c = 0; c < 2; ++c) {
      bool entered = c == 0 ? in0 : in1;
      if (!entered) continue;
      vec4 lo = c == 0 ? lo0 : lo1;
      vec4 hi = c == 0 ? hi0 : hi1;
      uint ref = floatBitsToUint(lo.w);
      uint count = floatBitsToUint(hi.w);
      if (count == 0u) {
        inner[innerCount] = ref;
        innerEntry[innerCount] = c == 0 ? e0 : e1;
        innerCount = innerCount + 1;
        continue;
      }
      best = intersectLeaf(w, origin, ref, count, best, anyHit BVH_ARG);
      if (anyHit && best.hit != 0u) {
        best.steps = steps;
        return best;
      }
    }
    // The nearer inner child is visited first (pushed last); a child whose
    // entry lies beyond a hit found meanwhile is skipped when popped.
    if (innerCount == 2) {
      bool swap = innerEntry[1] < innerEntry[0];
      stack[sp] = swap ? inner[0] : inner[1];
      stack[sp + 1] = swap ? inner[1] : inner[0];
      sp = sp + 2;
    } else if (innerCount == 1) {
      stack[sp] = inner[0];
      sp = sp + 1;
    }
  }
  best.steps = steps;
  if (best.hit == 0u) best.t = 0.0f;
  return best;
}

// The first hit within (0, tmax] along the unit direction `dir` (anyHit: any
// hit, the first found — for visibility) in a BVH of `width` children per
// node (2 or 4; node i is 2·width vec4 from 2·width·i). tmax may be +∞; a NaN
// or infinite origin or direction, a zero direction, or tmax < 0 or NaN: a miss.
SHARED_FN BvhHit traceBvhWidth(vec3 origin, vec3 dir, float tmax, bool anyHit, uint width BVH_PARAM) {
  if (width == 2u) return traceBvh2(origin, dir, tmax, anyHit BVH_ARG);
  if (!bvhRayValid(origin, dir, tmax)) return bvhMiss(0u);
  WatertightRay w = watertightRay(dir);
  vec3 invDir = bvhInvDir(dir);
  BvhHit best = bvhMiss(0u);
  // Finite, so that a missed box (entry +∞) stays beyond it, slack and all.
  best.t = min(tmax, kTraceInfinity);
  uint stack[kBvhStackSize];
  int sp = 0;
  stack[sp] = 0u;
  sp = sp + 1;
  uint steps = 0u;
  while (sp > 0) {
    sp = sp - 1;
    uint node = stack[sp];
    steps = steps + 1u;
    uint base = node * 2u * width;
    TRACE_FETCHES(2u * width, 32u * width);
    // Every child's box against the best hit so far, before any leaf of this node is tested.
    float entry[kBvhMaxWidth];
    bool entered[kBvhMaxWidth];
    for (uint c = 0u; c < width; ++c) {
      entry[c] = boxEntry(origin, invDir, bvhNodes[base + 2u * c], bvhNodes[base + 2u * c + 1u]);
      entered[c] = entry[c] <= best.t * kBoxSlack;
    }
    uint inner[kBvhMaxWidth];
    float innerEntry[kBvhMaxWidth];
    int innerCount = 0;
    for (uint c = 0u; c < width; ++c) {
      if (!entered[c]) continue;
      uint ref = floatBitsToUint(bvhNodes[base + 2u * c].w);
      uint count = floatBitsToUint(bvhNodes[base + 2u * c + 1u].w);
      if (count == 0u) {
        // Kept sorted by entry (insertion, stable: equal entries in child order).
        int j = innerCount;
        while (j > 0 && innerEntry[j - 1] > entry[c]) {
          inner[j] = inner[j - 1];
          innerEntry[j] = innerEntry[j - 1];
          j = j - 1;
        }
        inner[j] = ref;
        innerEntry[j] = entry[c];
        innerCount = innerCount + 1;
        continue;
      }
      best = intersectLeaf(w, origin, ref, count, best, anyHit BVH_ARG);
      if (anyHit && best.hit != 0u) {
        best.steps = steps;
        return best;
      }
    }
    // The nearest inner child is visited first (pushed last).
    for (int k = innerCount - 1; k >= 0; --k) {
      stack[sp] = inner[k];
      sp = sp + 1;
    }
  }
  best.steps = steps;
  if (best.hit == 0u) best.t = 0.0f;
  return best;
}

#ifndef __cplusplus
// The GLSL entry point: the BVH's width is a define of the program (BVH_WIDTH, 2 by default).
#ifndef BVH_WIDTH
#define BVH_WIDTH kBvhDefaultWidth
#endif
BvhHit traceBvh(vec3 origin, vec3 dir, float tmax, bool anyHit) {
  return traceBvhWidth(origin, dir, tmax, anyHit, BVH_WIDTH);
}
#endif

SHARED_END
