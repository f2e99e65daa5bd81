// Closed-box triangle–box overlap by separating axes (Akenine-Möller 2001) in
// float, for GPU voxelizers. (The CPU reference, voxelize/exact_voxelizer.cpp,
// runs the same test in double: it defines truth.) No arrays, so it compiles as
// GLSL and as C++.
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
SHARED_BEGIN

// True if the projections of triangle (a, b, c) and of the box (half size h,
// centred at the origin) onto `axis` are disjoint.
SHARED_FN bool separatedOnAxis(vec3 axis, vec3 a, vec3 b, vec3 c, vec3 h) {
  // precise: GPU and CPU must round alike (GLSL would fuse multiply-adds).
  SHARED_PRECISE float pa = dot(axis, a);
  SHARED_PRECISE float pb = dot(axis, b);
  SHARED_PRECISE float pc = dot(axis, c);
  SHARED_PRECISE float r = h.x * abs(axis.x) + h.y * abs(axis.y) + h.z * abs(axis.z);
  return min(pa, min(pb, pc)) > r || max(pa, max(pb, pc)) < -r;
}

SHARED_FN bool triangleOverlapsBox(vec3 center, vec3 h, vec3 a0, vec3 b0, vec3 c0) {
  vec3 a = a0 - center, b = b0 - center, c = c0 - center;
  vec3 e0 = b - a, e1 = c - b, e2 = a - c;
  vec3 ux = vec3(1.0f, 0.0f, 0.0f), uy = vec3(0.0f, 1.0f, 0.0f), uz = vec3(0.0f, 0.0f, 1.0f);
  if (separatedOnAxis(cross(ux, e0), a, b, c, h) || separatedOnAxis(cross(ux, e1), a, b, c, h) ||
      separatedOnAxis(cross(ux, e2), a, b, c, h) || separatedOnAxis(cross(uy, e0), a, b, c, h) ||
      separatedOnAxis(cross(uy, e1), a, b, c, h) || separatedOnAxis(cross(uy, e2), a, b, c, h) ||
      separatedOnAxis(cross(uz, e0), a, b, c, h) || separatedOnAxis(cross(uz, e1), a, b, c, h) ||
      separatedOnAxis(cross(uz, e2), a, b, c, h))
    return false;
  if (separatedOnAxis(ux, a, b, c, h) || separatedOnAxis(uy, a, b, c, h) || separatedOnAxis(uz, a, b, c, h))
    return false;
  SHARED_PRECISE vec3 n = cross(e0, e1);
  SHARED_PRECISE float d = abs(dot(n, a));
  SHARED_PRECISE float r = h.x * abs(n.x) + h.y * abs(n.y) + h.z * abs(n.z);
  return d <= r;
}

SHARED_END
