// reference_gl integrator=ao (illum/methods/reference_gl.cpp): the estimator of
// `reference integrator=ao` (illum/methods/reference.cpp, aoLi) on the GL
// device: per pixel and sample the camera ray's first hit x, one
// cosine-distributed direction about x's shading normal, 0 below the
// geometric plane, else 1 if no triangle lies within the radius (the start
// offset off the surface as the reference's).
#include "exact.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = IMAGE_SAMPLE) uniform image2D uImage;

void main() {
  ivec2 q;
  uint state;
  vec3 dir;
  if (!pixelRay(imageSize(uImage), q, state, dir)) return;
  float ao = 0.0f;
  const vec3 origin = primaryOrigin(dir);
  const BvhHit h = traceBvh(origin, dir, kTraceInfinity, false);
  if (h.hit != 0u) {
    const SurfaceNormals s = hitNormals(h, -dir);
    const vec3 p = origin + h.t * dir;
    vec2 u;
    u.x = rngNext(state);
    u.y = rngNext(state);
    const vec3 wi = basisToWorld(makeBasis(s.n), cosineSampleHemisphere(u));
    if (dot(wi, s.ng) > 0.0f) ao = occluded(offsetOffSurface(p, s.ng, wi, pass.eps), wi, pass.radius) ? 0.0f : 1.0f;
  }
  imageStore(uImage, q, vec4(vec3(ao), 1.0f));
}
