// A batch of rays through the tracer chosen by VGI_TRACER: for the tests
// (GPU == CPU bit for bit) and `vgi bench traverse`.
#include "tracer.glsl"
layout(local_size_x = 64) in;
struct Ray {
  vec3 origin;
  float tmax;
  vec3 dir;
  float pad;
};
#include "shared/bindings.glsl"
layout(std430, binding = BINDING_TRACE_RAYS) readonly buffer Rays { Ray rays[]; };
layout(std430, binding = BINDING_TRACE_HITS) writeonly buffer Hits { uvec4 hits[]; };  // 2 per ray
uniform uint uRayCount;
#ifdef TRACE_FROM_LEVEL
uniform uint uLevel;  // trace the pyramid from this level up (pyramidFromLevel)
#endif
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uRayCount) return;
#ifdef TRACE_FROM_LEVEL
  TraceHit h = tracePyramid(pyramidFromLevel(pyramidFromUniforms(), uLevel), rays[i].origin, rays[i].dir, rays[i].tmax);
#else
  TraceHit h = traceRay(rays[i].origin, rays[i].dir, rays[i].tmax);
#endif
  hits[2u * i] = uvec4(h.hit, floatBitsToUint(h.t), h.steps, 0u);
  hits[2u * i + 1u] = uvec4(h.voxel, 0u);
}
