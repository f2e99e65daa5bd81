#include "illum/resources/gpu_bvh.h"

#include <chrono>
#include <optional>

#include "core/profiler.h"
#include "core/scene.h"
#include "traverse/gpu_bvh.h"

namespace vgi {

namespace {

class GpuBvhResource : public Resource {
 public:
  bool update(SceneResources& res, const ResourceNeed&, Profiler& prof) override {
    if (builtFor_ && (!res.dynamic() || *builtFor_ == res.time())) return false;  // current
    {
      auto s = prof.scope("build_gpu_bvh");
      const auto t0 = std::chrono::steady_clock::now();
      arrays_ = buildBvh(flatten(res.scene(), res.time()));
      buildMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    }
    auto s = prof.scope("upload_gpu_bvh");
    if (!gpu_)
      gpu_ = std::make_unique<GpuBvh>(arrays_);
    else
      gpu_->upload(arrays_);
    builtFor_ = res.time();
    return true;
  }
  nlohmann::json stats() override {
    nlohmann::json j = arrays_.describe();
    j["cpu_build_ms"] = buildMs_;  // flatten + Embree's builder + our flattening into the GPU layout
    return j;
  }
  void* offer(const std::type_info& t) override { return offerOf(t, gpu_.get(), gpu_ ? &arrays_ : nullptr); }

 private:
  std::optional<float> builtFor_;
  BvhArrays arrays_;
  std::unique_ptr<GpuBvh> gpu_;
  double buildMs_ = 0;
};

}  // namespace

ResourceKind gpuBvhKind() {
  return {"gpu_bvh",
          "the scene's triangles in a BVH on the GPU (Embree's builder, Aila-Laine layout): tracer=bvh",
          [](const ResourceNeed&) { return std::vector<ResourceNeed>{}; },
          [](const ResourceNeed& n, const SceneNeeds&, const std::string& method, bool gl) {
            requireGl(n, method, gl);
          },
          [](const ResourceNeed&) { return std::vector<std::string>{"gpu_bvh"}; },
          [](const ResourceNeed&, SceneResources&) -> std::unique_ptr<Resource> {
            return std::make_unique<GpuBvhResource>();
          },
          "gpu_bvh"};
}

const ResourceKind& GpuBvhNeed::row() {
  static const ResourceKind k = gpuBvhKind();
  return k;
}

}  // namespace vgi
