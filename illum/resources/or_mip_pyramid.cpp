#include "illum/resources/or_mip_pyramid.h"

#include "core/profiler.h"
#include "traverse/gl_ray_tracer.h"
#include "traverse/or_mip_pyramid.h"
#include "voxelize/atlas_voxelizer.h"

namespace vgi {

namespace {

class OrMipPyramidResource : public Resource {
 public:
  explicit OrMipPyramidResource(const OrMipPyramidNeed& n) : grid_(n.grid) {}

  bool update(SceneResources& res, const ResourceNeed&, Profiler& prof) override {
    if ((gl_ || cpu_) && !res.changed(grid_)) return false;
    if (!res.gl()) {
      auto s = prof.scope("pyramid");
      cpu_ = std::make_unique<OrMipPyramid>(res.get<BinaryGrid>(grid_));
      return true;
    }
    if (!gl_) gl_ = std::make_unique<GlPyramid>(res.get<GridBox>(grid_));
    auto s = prof.scope("pyramid");
    if (const AtlasVoxelizer* atlas = res.tryGet<AtlasVoxelizer>(grid_))
      gl_->build(atlas->frameGrid(), res.shaders());
    else
      gl_->build(res.get<BinaryGrid>(grid_), res.shaders());
    return true;
  }
  void* offer(const std::type_info& t) override { return offerOf(t, gl_.get(), cpu_.get()); }
  nlohmann::json stats() override {
    if (gl_) return {{"levels", gl_->levels()}, {"bytes", gl_->bytes()}, {"memory", "gpu"}};
    if (cpu_) return {{"bytes", cpu_->words().size() * 4}, {"memory", "host"}};
    return nullptr;
  }

 private:
  BinaryGridNeed grid_;
  std::unique_ptr<GlPyramid> gl_;
  std::unique_ptr<OrMipPyramid> cpu_;
};

}  // namespace

ResourceKind orMipPyramidKind() {
  return {"or_mip_pyramid",
          "the OR-mip pyramid over a binary grid (level 0 the grid), what the voxel tracers traverse",
          [](const ResourceNeed& n) { return std::vector<ResourceNeed>{n.spec<OrMipPyramidNeed>().grid}; },
          [](const ResourceNeed&, const SceneNeeds&, const std::string&, bool) {},
          [](const ResourceNeed&) { return std::vector<std::string>{"or_mip_pyramid"}; },
          [](const ResourceNeed& n, SceneResources&) -> std::unique_ptr<Resource> {
            return std::make_unique<OrMipPyramidResource>(n.spec<OrMipPyramidNeed>());
          },
          "pyramid"};
}

const ResourceKind& OrMipPyramidNeed::row() {
  static const ResourceKind k = orMipPyramidKind();
  return k;
}

}  // namespace vgi
