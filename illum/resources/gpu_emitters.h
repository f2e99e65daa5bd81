// Resource kind "gpu_emitters": the scene's area lights (core/emitters.h) on
// the GPU, for the exact GL integrators (reference_gl): the emissive
// triangles as PackedEmitter rows (shaders/shared/emitters.glsl: corners,
// power CDF, area, front normal, Le) at BINDING_EMITTERS, and each triangle's
// emitter index in the flattened scene's order (−1: none) at BINDING_EMITTER_OF,
// the order the BVH reports hits in. Made again at each time of a scene with
// dynamic meshes. Offers GpuEmitters.
#pragma once
#include <cstddef>
#include <nlohmann/json.hpp>

#include "illum/framework/resources.h"

namespace vgi {

class Emitters;

class GpuEmitters {
 public:
  GpuEmitters() = default;
  ~GpuEmitters();
  GpuEmitters(const GpuEmitters&) = delete;
  GpuEmitters& operator=(const GpuEmitters&) = delete;
  void upload(const Emitters& emitters);
  void bind() const;
  size_t count() const { return count_; }
  size_t bytes() const { return bytes_; }

 private:
  unsigned buffers_[2] = {0, 0};
  size_t count_ = 0, bytes_ = 0;
};

struct GpuEmittersNeed {
  static constexpr const char* kKind = "gpu_emitters";
  static const ResourceKind& row();  // its row of the kinds table (gpuEmittersKind())
  nlohmann::json key() const { return nlohmann::json::object(); }
};

ResourceKind gpuEmittersKind();

}  // namespace vgi
