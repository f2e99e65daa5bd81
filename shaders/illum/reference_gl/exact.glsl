// What the exact GL integrators share (illum/methods/reference_gl.cpp): the
// scene's triangles in the BVH (shared/trace_bvh.glsl), the camera ray of a
// pixel and sample as the CPU reference draws it, and the two-sided normals
// at a hit (shared/exact_surface.glsl).
#include "shared/bindings.glsl"
#include "shared/constants.glsl"
#include "shared/sampling.glsl"
#include "shared/ray_grid.glsl"
#include "shared/exact_surface.glsl"
layout(std430, binding = BINDING_BVH_NODES) readonly buffer BvhNodes { vec4 bvhNodes[]; };
layout(std430, binding = BINDING_BVH_TRIS) readonly buffer BvhTris { vec4 bvhTris[]; };
layout(std430, binding = BINDING_BVH_NORMALS) readonly buffer BvhNormals { vec4 bvhNormals[]; };
#include "shared/trace_bvh.glsl"

#include "params.glsl"
layout(std140, binding = UBO_PASS) uniform Pass { ReferenceGlParams pass; };

// The camera ray through a uniformly random point of pixel q (seeded, as the
// reference's: a box filter sampled at random, not the sample loop's
// seed-independent Halton jitter). GL rows run bottom-up: row q.y is the
// reference's row H − 1 − q.y.
vec3 cameraRay(ivec2 q, ivec2 size, inout uint state) {
  vec2 jitter;
  jitter.x = rngNext(state);
  jitter.y = rngNext(state);
  const vec2 ndc = (vec2(q) + jitter) / vec2(size) * 2.0f - 1.0f;
  return normalize(pass.forward.xyz + ndc.x * pass.right.xyz + ndc.y * pass.up.xyz);
}

// Where the camera ray along dir starts: the eye, or its point on a cut-away camera's near plane.
vec3 primaryOrigin(vec3 dir) { return pass.eye.w > 0.0f ? pass.eye.xyz + dir * (pass.eye.w / dot(dir, pass.forward.xyz)) : pass.eye.xyz; }

// This invocation's pixel q of an image of `size`, its random stream (per
// pixel, sample and seed) and its camera ray; false outside the image.
bool pixelRay(ivec2 size, out ivec2 q, out uint rng, out vec3 dir) {
  q = ivec2(gl_GlobalInvocationID.xy);
  if (q.x >= size.x || q.y >= size.y) return false;
  rng = rngSeed(uint(q.y * size.x + q.x), pass.sampleIndex, pass.seed);
  dir = cameraRay(q, size, rng);
  return true;
}

// The normals of hit h's triangle at the hit, facing wo (towards the viewer).
SurfaceNormals hitNormals(BvhHit h, vec3 wo) {
  const uint t = h.triangle;
  const vec4 n0 = bvhNormals[3u * t], n1 = bvhNormals[3u * t + 1u], n2 = bvhNormals[3u * t + 2u];
  const float w = 1.0f - h.u - h.v;
  return orientNormals(vec3(n0.w, n1.w, n2.w), w * n0.xyz + h.u * n1.xyz + h.v * n2.xyz, wo);
}

bool occluded(vec3 o, vec3 dir, float tmax) { return traceBvh(o, dir, tmax, true).hit != 0u; }
