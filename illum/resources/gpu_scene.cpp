#include "illum/resources/gpu_scene.h"

#include "core/gpu_scene.h"
#include "core/profiler.h"
#include "illum/framework/sample_loop.h"

namespace vgi {

namespace {
class GpuSceneResource : public Resource {
 public:
  bool update(SceneResources& res, const ResourceNeed&, Profiler& prof) override {
    auto s = prof.scope("upload");
    if (!gpu_)
      gpu_ = std::make_unique<GpuScene>(res.scene(), res.time());
    else
      gpu_->setTime(res.scene(), res.time());
    gpu_->setLights(res.lights());
    return true;
  }
  bool relight(SceneResources& res, const ResourceNeed&, Profiler&) override {
    gpu_->setLights(res.lights());
    return true;
  }
  void* offer(const std::type_info& t) override { return offerOf(t, gpu_.get()); }

 private:
  std::unique_ptr<GpuScene> gpu_;
};
}  // namespace

void gpuSceneInput(Frame& f, unsigned program) { f.resources.get<GpuScene>().bind(f.shaders(), program); }

void needGBuffer(SceneNeeds& needs) {
  needs.gbuffer = true;
  needs.add(GpuSceneNeed{});
}

ResourceKind gpuSceneKind() {
  return {
      "gpu_scene",
      "the scene's triangles, materials and GL lights on the GPU (G-buffer, light maps, rasterizing passes)",
      [](const ResourceNeed&) { return std::vector<ResourceNeed>{}; },
      [](const ResourceNeed& n, const SceneNeeds&, const std::string& method, bool gl) {
        requireGl(n, method, gl);
      },
      [](const ResourceNeed&) { return std::vector<std::string>{"gpu_scene"}; },
      [](const ResourceNeed&, SceneResources&) -> std::unique_ptr<Resource> {
        return std::make_unique<GpuSceneResource>();
      },
      "",
      true};
}

const ResourceKind& GpuSceneNeed::row() {
  static const ResourceKind k = gpuSceneKind();
  return k;
}

}  // namespace vgi
