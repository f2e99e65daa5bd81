// The exact methods' conventions at a surface point, one source for the CPU
// reference (illum/methods/reference.cpp) and the GL one (reference_gl's
// shaders): surfaces are two-sided, so the geometric normal turns towards the
// viewer and the shading normal to its side (a degenerate one becomes the
// geometric normal); a ray leaves the surface from a point offset along the
// geometric normal on its side, by the scene's ε plus the coordinates' float
// spacing (against self-hits).
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
#include "ray_grid.glsl"
SHARED_BEGIN

struct SurfaceNormals {
  vec3 n;   // shading, unit
  vec3 ng;  // geometric, unit
};

// ng: the unit geometric normal as stored; interpolated: the corners' shading
// normals weighted by the barycentrics (not normalized); wo: towards the viewer.
SHARED_FN SurfaceNormals orientNormals(vec3 ng, vec3 interpolated, vec3 wo) {
  SurfaceNormals s;
  s.ng = dot(ng, wo) < 0.0f ? -ng : ng;
  s.n = normalize(interpolated);
  if (!isFiniteFloat(s.n.x) || dot(s.n, s.ng) < 0.0f) s.n = -s.n;
  if (!isFiniteFloat(s.n.x)) s.n = s.ng;
  return s;
}

// Where a ray towards `dir` starts from surface point p with geometric normal ng.
SHARED_FN vec3 offsetOffSurface(vec3 p, vec3 ng, vec3 dir, float eps) {
  float scale = eps + 1e-6f * max(max(abs(p.x), abs(p.y)), abs(p.z));
  return p + (dot(dir, ng) >= 0.0f ? scale : -scale) * ng;
}

SHARED_END
