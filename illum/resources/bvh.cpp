#include "illum/resources/bvh.h"

#include <optional>

#include "core/emitters.h"
#include "core/profiler.h"
#include "core/scene.h"
#include "traverse/embree_tracer.h"

namespace vgi {

namespace {

class BvhResource : public Resource {
 public:
  bool update(SceneResources& res, const ResourceNeed&, Profiler& prof) override {
    if (builtFor_ && (!res.dynamic() || *builtFor_ == res.time())) return false;  // current
    auto s = prof.scope("build_bvh");
    tracer_.reset();
    flat_ = std::make_unique<FlatScene>(flatten(res.scene(), res.time()));
    tracer_ = std::make_unique<EmbreeTracer>(*flat_);
    emitters_ = std::make_unique<Emitters>(res.scene(), *flat_);
    builtFor_ = res.time();
    return true;
  }
  void* offer(const std::type_info& t) override {
    return offerOf(t, tracer_.get(), flat_.get(), emitters_.get());
  }

 private:
  std::optional<float> builtFor_;
  std::unique_ptr<FlatScene> flat_;
  std::unique_ptr<EmbreeTracer> tracer_;
  std::unique_ptr<Emitters> emitters_;
};

}  // namespace

ResourceKind bvhKind() {
  return {"bvh",
          "the flattened scene in an Embree BVH on the CPU, with its area lights (exact visibility)",
          [](const ResourceNeed&) { return std::vector<ResourceNeed>{}; },
          [](const ResourceNeed&, const SceneNeeds&, const std::string&, bool) {},
          [](const ResourceNeed&) { return std::vector<std::string>{"bvh"}; },
          [](const ResourceNeed&, SceneResources&) -> std::unique_ptr<Resource> {
            return std::make_unique<BvhResource>();
          },
          ""};
}

const ResourceKind& BvhNeed::row() {
  static const ResourceKind k = bvhKind();
  return k;
}

}  // namespace vgi
