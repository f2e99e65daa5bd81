// The approximate visibility grid (Bashford-Rogers et al. 2011, §III-A; the
// `avg` module): per cell the sums of the unit normals and the albedos of the
// triangles that overlap it, and their count — summed (additively, as the
// paper blends), normalised where read. Fixed point so the GPU can add them
// with integer atomics: 8 uints per cell, x fastest then y then z:
//   0–2 Σ normal (two's-complement int, × avgFixedScale), 3–5 Σ albedo
//   (× avgFixedScale), 6 the count, 7 unused.
// At 2^16 per unit a cell holds 32767 triangles before a normal sum overflows.
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif

SHARED_BEGIN

SHARED_FN float avgFixedScale() { return 65536.0f; }
SHARED_FN uint avgCellBase(uvec3 c, uvec3 res) { return 8u * (c.x + res.x * (c.y + res.y * c.z)); }
// The mean of `count` fixed-point sums.
SHARED_FN vec3 avgMean(ivec3 sum, uint count) {
  return count == 0u ? vec3(0.0f) : vec3(sum) * (1.0f / (avgFixedScale() * float(count)));
}

// The normal of a VPL that a ray of direction d places in a cell whose mean
// unit normal is `mean` (avgMean of the normal sums: its length says how well
// the cell's triangles agree). A surface the ray meets faces it, so a mean
// that faces the ray is the VPL's normal. One that faces away means either a
// sheet seen from its other side (the triangles agree: |mean| >= 0.9) —
// the normal turned round — or a cell holding faces of several orientations,
// an edge or a corner, where the faces turned away from the ray (the slab's
// underside at the rim of an opening, a wall behind a floor) outweigh the one
// it meets. Turning such a mean round points it into the solid: the VPL then
// lights the solid's inside and its shadow map, lifted along that normal, looks
// at the face it meets from behind — the hot pixels on the atrium's rim (issue
// 64 §1). Instead the part of the mean along the ray is reversed and its part
// across the ray kept (the mean reflected in the plane normal to d): the
// edge's face turned to the ray, within the information a mean holds. An
// empty mean gives -d.
SHARED_FN vec3 avgVplNormal(vec3 mean, vec3 d) {
  float m = length(mean);
  if (!(m > 1e-3f)) return -d;
  vec3 n = mean / m;
  float c = dot(n, d);
  if (c <= 0.0f) return n;
  if (m >= 0.9f) return -n;
  vec3 r = n - 2.0f * c * d;
  return normalize(r);
}

SHARED_END
