// The ray tracers behind one interface (VGI §4 and its alternatives):
//   hierarchical  first hit over the OR-mip pyramid (shaders/shared/trace_hierarchical.glsl)
//   dda           3D DDA over level 0, the oracle on the grid (trace_dda.glsl)
//   march         fixed-step ray marching as in the AVG paper (trace_march.glsl)
//   bvh           exact first hit on the triangles through our BVH (shaders/shared/trace_bvh.glsl:
//                 GLSL and C++ from one source; traverse/gpu_bvh.h)
//   embree        exact first hit on the triangles (C++ only)
//   bricks        first hit through 4³ bricks (shaders/shared/trace_bricks.glsl; C++ only so far)
// The voxel tracers run the same shared kernels the GLSL passes compile (the
// tracer is chosen there by a define, see gl_ray_tracer.h), so what the tests
// check is what the GPU runs. Directions should be unit length: t and tmax are
// in units of |dir| (world distance for unit directions).
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

#include "shaders/shared/or_mip.glsl"

namespace vgi {

class OrMipPyramid;
struct GridBox;
class EmbreeTracer;
struct BvhArrays;

// std430-compatible: { vec3 origin; float tmax; vec3 dir; float pad; }.
struct TraceRay {
  glm::vec3 origin{0.0f};
  float tmax = 0.0f;
  glm::vec3 dir{0.0f, 0.0f, 1.0f};
  float pad = 0.0f;
};
static_assert(sizeof(TraceRay) == 32, "TraceRay must match the std430 layout");

struct TraceResult {
  bool hit = false;
  float t = 0.0f;        // distance to the entry of the hit voxel (bvh, embree: to the surface)
  glm::uvec3 voxel{0u};  // the hit voxel (bvh, embree: the voxel holding the hit point)
  uint32_t steps = 0;    // loop iterations (0 for embree)
};

struct TracerInfo {
  std::string name;
  std::string description;
  bool glsl;   // also available in GLSL passes (selected by a define)
  int define;  // value of VGI_TRACER in GLSL
};
const std::vector<TracerInfo>& tracerRegistry();
// Throws naming `what` (e.g. "tracer" or "--tracers") and the value, listing the choices.
const TracerInfo& findTracer(const std::string& name, const std::string& what = "tracer");

// What a tracer may need; the voxel tracers need `pyramid`, embree needs
// `embree`, bvh needs `bvh` (and the pyramid's grid, if given, names the hit voxels).
struct TracerInputs {
  const OrMipPyramid* pyramid = nullptr;
  const EmbreeTracer* embree = nullptr;
  const BvhArrays* bvh = nullptr;
  float marchStep = 0.0f;  // world units; 0: half the smallest voxel edge
  // Voxel tracers: trace the pyramid from this level up, its columns as the
  // voxels (shared pyramidFromLevel; results name level-`level` cells).
  uint32_t level = 0;
};

class RayTracer {
 public:
  virtual ~RayTracer() = default;
  virtual TraceResult trace(const TraceRay& ray) const = 0;
  // Many rays on `threads` CPU threads (0: all cores); results in ray order.
  void traceBatch(const std::vector<TraceRay>& rays, std::vector<TraceResult>& out, int threads = 0) const;
  // The same, counting per ray what the shared kernel loads and how it moves through the levels
  // (shared::TraceCounts; all zero for embree, which runs no shared kernel).
  void countBatch(const std::vector<TraceRay>& rays, std::vector<TraceResult>& out,
                  std::vector<shared::TraceCounts>& counts, int threads = 0) const;
};

std::unique_ptr<RayTracer> createTracer(const std::string& name, const TracerInputs& inputs);

// The pyramid as the shared kernels read it.
shared::PyramidParams pyramidParams(const GridBox& box);
shared::PyramidParams pyramidParams(const OrMipPyramid& pyramid);
// Default march step: half the smallest voxel edge of the grid.
float defaultMarchStep(const GridBox& box);
float defaultMarchStep(const OrMipPyramid& pyramid);

}  // namespace vgi
