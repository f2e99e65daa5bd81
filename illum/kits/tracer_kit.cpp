#include "illum/kits/tracer_kit.h"

#include "core/error.h"
#include "illum/resources/gpu_bvh.h"
#include "illum/resources/or_mip_pyramid.h"
#include "illum/resources/value_grids.h"
#include "shaders/shared/bindings.glsl"
#include "traverse/gl_ray_tracer.h"
#include "traverse/gpu_bvh.h"

namespace vgi {

void addTracerNeeds(SceneNeeds& n, const BinaryGridNeed& grid, const std::string& tracer) {
  n.add(OrMipPyramidNeed{grid});
  if (tracer == "bvh") n.add(GpuBvhNeed{});
}

void addVoxelHitNeeds(SceneNeeds& needs, BinaryGridNeed grid, const std::string& tracer,
                      std::vector<std::string> values) {
  grid.values = std::move(values);
  addTracerNeeds(needs, grid, tracer);
  needs.add(ValueGridNeed{grid, ValueMips::None, std::nullopt});
}

void bindTracer(const SceneResources& res, ShaderLibrary& shaders, unsigned program) {
  res.get<GlPyramid>().bind(shaders, program);
  if (const GpuBvh* bvh = res.tryGet<GpuBvh>()) bvh->bind();
}

int hitPointConstant(const std::string& name) {
  if (name == "entry") return shared::VOXEL_HIT_ENTRY;
  if (name == "centre") return shared::VOXEL_HIT_CENTRE;
  if (name == "plane") return shared::VOXEL_HIT_PLANE;
  fail("unknown hitpoint '", name, "'");  // the parameter's choices are checked when it is read
}

void VoxelHits::set(unsigned program, const shared::VoxelHitParams& params) {
  checkBlockLayout(program, "VoxelHits", sizeof params, "illum/voxel_hits.glsl");
  block_.value = params;
  block_.upload();
}

void VoxelHits::bind() const { block_.buffer().bind(UBO_VOXEL_HITS); }

}  // namespace vgi
