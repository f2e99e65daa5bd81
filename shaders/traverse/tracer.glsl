// The tracer a GLSL pass uses, chosen at compile time by VGI_TRACER (one of
// the ids in shared/tracer_ids.glsl, as traverse/ray_tracers.cpp's registry
// sets it; any other value fails to compile):
//   TraceHit traceRay(vec3 origin, vec3 dir, float tmax)
//   TraceHit tracePyramid(PyramidParams p, …)  the same over p (pyramidFromLevel: a mip level)
//   bool visibleBetween(vec3 a, vec3 b)
//   ResumableRay: nextHit / passHit (rays that go on past voxels a module passes)
// The pyramid and its parameters are bound by GlPyramid::bind (traverse/gl_ray_tracer.cpp);
// with VGI_TRACER_BVH the rays meet the scene's triangles (exact visibility,
// shared/trace_bvh.glsl; GpuBvh::bind) and the pyramid gives the grid their
// hits are reported in.
#include "shared/tracer_ids.glsl"
#ifndef VGI_TRACER
#define VGI_TRACER VGI_TRACER_HIERARCHICAL
#endif
#include "shared/voxel_grid.glsl"
#include "shared/or_mip.glsl"
#include "shared/ray_grid.glsl"
layout(std430, binding = BINDING_PYRAMID) readonly buffer PyramidWords { uint pyramidWords[]; };
#include "shared/trace_hierarchical.glsl"
#include "shared/trace_dda.glsl"
#include "shared/trace_march.glsl"
#if VGI_TRACER == VGI_TRACER_BVH
layout(std430, binding = BINDING_BVH_NODES) readonly buffer BvhNodes { vec4 bvhNodes[]; };
layout(std430, binding = BINDING_BVH_TRIS) readonly buffer BvhTris { vec4 bvhTris[]; };
#include "shared/trace_bvh.glsl"
// The exact first hit on the triangles, reported as the voxel tracers report
// theirs: t is the distance to the surface, `voxel` the grid cell that holds
// the hit point (so value-grid lookups and passHit work unchanged).
TraceHit traceBvhAsVoxels(GridParams g, vec3 origin, vec3 dir, float tmax) {
  BvhHit b = traceBvh(origin, dir, tmax, false);
  if (b.hit == 0u) return traceMiss(b.steps);
  TraceHit h;
  h.hit = 1u;
  h.t = b.t;
  precise vec3 p = origin + b.t * dir;
  h.voxel = gridCell(g, worldToGrid(g, p));
  h.steps = b.steps;
  return h;
}
#endif
#include "voxelize/grid_uniforms.glsl"
uniform uint uPyramidLevels;
uniform uint uPyramidOffsets[16];
uniform float uMarchStep;

PyramidParams pyramidFromUniforms() {
  PyramidParams p;
  p.grid = gridFromUniforms();
  p.levels = uPyramidLevels;
  for (int i = 0; i < 16; ++i) p.levelOffsets[i] = uPyramidOffsets[i];
  return p;
}

TraceHit tracePyramid(PyramidParams p, vec3 origin, vec3 dir, float tmax) {
#if VGI_TRACER == VGI_TRACER_HIERARCHICAL
  return traceHierarchical(p, origin, dir, tmax);
#elif VGI_TRACER == VGI_TRACER_DDA
  return traceDda(p, origin, dir, tmax);
#elif VGI_TRACER == VGI_TRACER_MARCH
  return traceMarch(p, origin, dir, tmax, uMarchStep);
#elif VGI_TRACER == VGI_TRACER_BVH
  return traceBvhAsVoxels(p.grid, origin, dir, tmax);  // (the triangles have no levels)
#else
#error "unknown VGI_TRACER (ids: shaders/shared/tracer_ids.glsl)"
#endif
}

TraceHit traceRay(vec3 origin, vec3 dir, float tmax) { return tracePyramid(pyramidFromUniforms(), origin, dir, tmax); }

// No voxel set on the segment a–b (the tracers take a unit direction and a
// length); bvh: no triangle on it (any hit ends the search).
bool visibleBetween(vec3 a, vec3 b) {
  float len = length(b - a);
#if VGI_TRACER == VGI_TRACER_BVH
  return len <= 0.0f || traceBvh(a, (b - a) / len, len, true).hit == 0u;
#else
  return len <= 0.0f || traceRay(a, (b - a) / len, len).hit == 0u;
#endif
}

// A ray that may go on past voxels its module judges empty (a voxel a light
// sees through) or the receiver's own: nextHit() traces from where the ray
// stands; after a hit the module stops, or calls passHit() to resume just
// past that voxel (its exit distance plus 1e-4 of a voxel diagonal), at most
// kMaxPasses times. A ray resumed past the radius has no next hit.
// `precise`: the resumed origins are rounded without fused multiply-adds, the
// way the tracers' shared code computes.
const int kMaxPasses = 3;
struct ResumableRay {
  vec3 origin, dir;
  float radius, start;  // start: where the current trace begins, along dir
  int passes;
  TraceHit hit;         // of the last nextHit()
};
ResumableRay resumableRay(vec3 origin, vec3 dir, float radius) {
  ResumableRay r;
  r.origin = origin;
  r.dir = dir;
  r.radius = radius;
  r.start = 0.0f;
  r.passes = 0;
  r.hit.hit = 0u;
  return r;
}
bool nextHit(inout ResumableRay r) {
  if (r.start >= r.radius) return false;
  precise vec3 from = r.origin + r.start * r.dir;
  precise float left = r.radius - r.start;
  r.hit = traceRay(from, r.dir, left);
  return r.hit.hit != 0u;
}
// The last hit's distance from the ray's origin.
float hitDistance(ResumableRay r) {
  precise float t = r.start + r.hit.t;
  return t;
}
bool passHit(inout ResumableRay r, float voxelDiagonal) {
  if (r.passes == kMaxPasses) return false;
  ++r.passes;
  precise vec3 from = r.origin + r.start * r.dir;
  precise float left = r.radius - r.start;
  GridRay gr = prepareGridRay(gridFromUniforms(), from, r.dir, left);
  precise float step = voxelExitT(gr, r.hit.voxel) + 1e-4f * voxelDiagonal;
  r.start += step;
  return true;
}
