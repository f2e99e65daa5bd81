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
  static const ResourceKind& row();  // its row of the kinds table (gpuSceneKind())
  nlohmann::json key() const { return nlohmann::json::object(); }
};

ResourceKind gpuSceneKind();

class Frame;
// A compute pass's input (illum/framework/compute_pass.h): the GPU scene bound to the program.
void gpuSceneInput(Frame& f, unsigned program);
// A method that draws the G-buffer (the sample loop renders it before each sample, from the GPU
// scene): sets needs.gbuffer and adds the GPU scene it draws.
void needGBuffer(SceneNeeds& needs);

}  // namespace vgi
