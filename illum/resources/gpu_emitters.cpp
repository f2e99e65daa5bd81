#include "illum/resources/gpu_emitters.h"

#include <glad/gl.h>

#include <algorithm>
#include <optional>

#include "core/emitters.h"
#include "core/profiler.h"
#include "core/scene.h"
#include "shaders/shared/bindings.glsl"

namespace vgi {

static_assert(sizeof(shared::PackedEmitter) == 80, "std430 layout of PackedEmitter");

GpuEmitters::~GpuEmitters() { glDeleteBuffers(2, buffers_); }

void GpuEmitters::upload(const Emitters& emitters) {
  const std::vector<shared::PackedEmitter> rows = emitters.packed();
  const std::vector<int>& of = emitters.emitterOfTriangles();
  glDeleteBuffers(2, buffers_);
  glCreateBuffers(2, buffers_);
  const void* data[2] = {rows.data(), of.data()};
  const size_t bytes[2] = {rows.size() * sizeof(rows[0]), of.size() * sizeof(int)};
  bytes_ = 0;
  for (int i = 0; i < 2; ++i) {
    // A zero-sized buffer cannot be bound: keep one row of padding.
    glNamedBufferStorage(buffers_[i], GLsizeiptr(std::max<size_t>(bytes[i], sizeof(rows[0]))), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    if (bytes[i]) glNamedBufferSubData(buffers_[i], 0, GLsizeiptr(bytes[i]), data[i]);
    bytes_ += bytes[i];
  }
  count_ = rows.size();
}

void GpuEmitters::bind() const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_EMITTERS, buffers_[0]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_EMITTER_OF, buffers_[1]);
}

namespace {

class GpuEmittersResource : public Resource {
 public:
  bool update(SceneResources& res, const ResourceNeed&, Profiler& prof) override {
    if (builtFor_ && (!res.dynamic() || *builtFor_ == res.time())) return false;  // current
    auto s = prof.scope("upload_gpu_emitters");
    // The whole scene is flattened (not only its emissive meshes) for the triangle -> emitter map.
    gpu_.upload(Emitters(res.scene(), flatten(res.scene(), res.time())));
    builtFor_ = res.time();
    return true;
  }
  nlohmann::json stats() override { return {{"emitters", gpu_.count()}, {"bytes", gpu_.bytes()}}; }
  void* offer(const std::type_info& t) override { return offerOf(t, &gpu_); }

 private:
  std::optional<float> builtFor_;
  GpuEmitters gpu_;
};

}  // namespace

ResourceKind gpuEmittersKind() {
  return {"gpu_emitters",
          "the scene's area lights on the GPU (emissive triangles, power CDF, triangle -> emitter): "
          "reference_gl",
          [](const ResourceNeed&) { return std::vector<ResourceNeed>{}; },
          [](const ResourceNeed& n, const SceneNeeds&, const std::string& method, bool gl) {
            requireGl(n, method, gl);
          },
          [](const ResourceNeed&) { return std::vector<std::string>{"gpu_emitters"}; },
          [](const ResourceNeed&, SceneResources&) -> std::unique_ptr<Resource> {
            return std::make_unique<GpuEmittersResource>();
          },
          "gpu_emitters"};
}

const ResourceKind& GpuEmittersNeed::row() {
  static const ResourceKind k = gpuEmittersKind();
  return k;
}

}  // namespace vgi
