// reference_gl integrator=ao (illum/methods/reference_gl.cpp): the estimator of
// `reference integrator=ao` (illum/methods/reference.cpp, aoLi) on the GL
// device, through the scene's triangles in the BVH (shared/trace_bvh.glsl):
// per pixel and sample the camera ray through a uniformly random point of the
// pixel (seeded, as the reference's: a box filter sampled at random, not the
// loop's seed-independent Halton jitter), its first hit x, one cosine-distributed direction about
// x's shading normal, 0 below the geometric plane, else 1 if no triangle lies
// within the radius (the start offset off the surface as the reference's).
#include "../../shared/bindings.glsl"
#include "../../shared/constants.glsl"
#include "../../shared/sampling.glsl"
#include "../../shared/ray_grid.glsl"
#include "../../shared/exact_surface.glsl"
layout(std430, binding = BINDING_BVH_NODES) readonly buffer BvhNodes { vec4 bvhNodes[]; };
layout(std430, binding = BINDING_BVH_TRIS) readonly buffer BvhTris { vec4 bvhTris[]; };
layout(std430, binding = BINDING_BVH_NORMALS) readonly buffer BvhNormals { vec4 bvhNormals[]; };
#include "../../shared/trace_bvh.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = IMAGE_SAMPLE) uniform image2D uImage;

uniform vec3 uEye, uFwd;
uniform vec3 uRight, uUp;  // scaled by tan(fov/2)·aspect and tan(fov/2) (illum/framework/deferred.h, PinholeView)
uniform float uRadius;  // world units
uniform float uEps;     // the start offset's scene part (2e-5 of the diagonal)
uniform uint uSample;
uniform uint uSeed;

void main() {
  const ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  const ivec2 size = imageSize(uImage);
  if (q.x >= size.x || q.y >= size.y) return;
  uint state = rngSeed(uint(q.y * size.x + q.x), uSample, uSeed);
  vec2 jitter;
  jitter.x = rngNext(state);
  jitter.y = rngNext(state);
  // GL rows run bottom-up: row q.y is the reference's row H − 1 − q.y.
  const vec2 ndc = (vec2(q) + jitter) / vec2(size) * 2.0f - 1.0f;
  const vec3 dir = normalize(uFwd + ndc.x * uRight + ndc.y * uUp);
  float ao = 0.0f;
  const BvhHit h = traceBvh(uEye, dir, kTraceInfinity, false);
  if (h.hit != 0u) {
    const uint t = h.triangle;
    const vec4 n0 = bvhNormals[3u * t], n1 = bvhNormals[3u * t + 1u], n2 = bvhNormals[3u * t + 2u];
    const float w = 1.0f - h.u - h.v;
    const SurfaceNormals s = orientNormals(vec3(n0.w, n1.w, n2.w), w * n0.xyz + h.u * n1.xyz + h.v * n2.xyz, -dir);
    const vec3 p = uEye + h.t * dir;
    vec2 u;
    u.x = rngNext(state);
    u.y = rngNext(state);
    const vec3 wi = basisToWorld(makeBasis(s.n), cosineSampleHemisphere(u));
    if (dot(wi, s.ng) > 0.0f) ao = traceBvh(offsetOffSurface(p, s.ng, wi, uEps), wi, uRadius, true).hit != 0u ? 0.0f : 1.0f;
  }
  imageStore(uImage, q, vec4(vec3(ao), 1.0f));
}
