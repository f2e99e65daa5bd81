// Resource kind "gpu_scene": the scene's triangles, materials and the GL
// lights on the GPU (core/gpu_scene.h), kept current for the animation time
// and the lights SceneResources places. What the G-buffer, the light maps and
// every rasterizing pass draw.
#pragma once
#include <nlohmann/json.hpp>

#include "illum/framework/resources.h"

namespace vgi {

struct GpuSceneNeed {
  static constexpr const char* kKind = "gpu_scene";
  nlohmann::json key() const { return nlohmann::json::object(); }
};

ResourceKind gpuSceneKind();

}  // namespace vgi
