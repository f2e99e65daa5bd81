#include "illum/kits/tracer_kit.h"

#include "illum/resources/gpu_bvh.h"
#include "illum/resources/or_mip_pyramid.h"
#include "traverse/gl_ray_tracer.h"
#include "traverse/gpu_bvh.h"

namespace vgi {

void addTracerNeeds(SceneNeeds& n, const BinaryGridNeed& grid, const std::string& tracer) {
  n.add(OrMipPyramidNeed{grid});
  if (tracer == "bvh") n.add(GpuBvhNeed{});
}

void bindTracer(const SceneResources& res, ShaderLibrary& shaders, unsigned program) {
  res.get<GlPyramid>().bind(shaders, program);
  if (const GpuBvh* bvh = res.tryGet<GpuBvh>()) bvh->bind();
}

}  // namespace vgi
