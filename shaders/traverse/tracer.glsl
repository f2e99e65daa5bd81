// The tracer a GLSL pass uses, chosen at compile time by VGI_TRACER (one of
// the ids in shared/tracer_ids.glsl, as traverse/ray_tracers.cpp's registry
// sets it; any other value fails to compile):
//   TraceHit traceRay(vec3 origin, vec3 dir, float tmax)
//   bool visibleBetween(vec3 a, vec3 b)
//   float exitPastHit(vec3 origin, vec3 dir, float tmax, TraceHit hit, float voxelDiagonal)
// The pyramid and its parameters are bound by GlPyramid::bind (traverse/gl_ray_tracer.cpp).
#include "../shared/tracer_ids.glsl"
#ifndef VGI_TRACER
#define VGI_TRACER VGI_TRACER_HIERARCHICAL
#endif
#include "../shared/voxel_grid.glsl"
#include "../shared/or_mip.glsl"
#include "../shared/ray_grid.glsl"
layout(std430, binding = BINDING_PYRAMID) readonly buffer PyramidWords { uint pyramidWords[]; };
#include "../shared/trace_hierarchical.glsl"
#include "../shared/trace_dda.glsl"
#include "../shared/trace_march.glsl"
#include "../voxelize/grid_uniforms.glsl"
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

TraceHit traceRay(vec3 origin, vec3 dir, float tmax) {
  PyramidParams p = pyramidFromUniforms();
#if VGI_TRACER == VGI_TRACER_HIERARCHICAL
  return traceHierarchical(p, origin, dir, tmax);
#elif VGI_TRACER == VGI_TRACER_DDA
  return traceDda(p, origin, dir, tmax);
#elif VGI_TRACER == VGI_TRACER_MARCH
  return traceMarch(p, origin, dir, tmax, uMarchStep);
#else
#error "unknown VGI_TRACER (ids: shaders/shared/tracer_ids.glsl)"
#endif
}

bool visibleBetween(vec3 a, vec3 b) { return traceRay(a, b - a, 1.0f).hit == 0u; }

// How far along (origin, dir) a ray resumed past the voxel `hit` starts: the
// voxel's exit distance plus 1e-4 of a voxel diagonal (modules that pass
// voxels they judge empty or their receiver's own). `precise`: rounded
// without fused multiply-adds, as the tracers' shared code computes.
float exitPastHit(vec3 origin, vec3 dir, float tmax, TraceHit hit, float voxelDiagonal) {
  GridRay gr = prepareGridRay(gridFromUniforms(), origin, dir, tmax);
  precise float t = voxelExitT(gr, hit.voxel) + 1e-4f * voxelDiagonal;
  return t;
}
