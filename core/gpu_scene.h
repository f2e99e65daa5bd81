// The scene uploaded for the GL modules: one non-indexed vertex buffer
// (position, normal, uv per corner, world space at one instant), materials and
// lights as std430 SSBOs (shaders/shared/gpu_scene.glsl), albedo textures as one
// 2D array (resampled to the largest size), the environment map.
#pragma once
#include "core/scene.h"
#include "shaders/shared/gpu_scene.glsl"

namespace vgi {
class ShaderLibrary;

shared::PackedLight packLight(const Light& light);
// emission.w = 1 where the material emits from both sides (Scene::twoSidedEmission).
shared::PackedMaterial packMaterial(const Material& m, int textureLayer, bool twoSidedEmission);

class GpuScene {
 public:
  GpuScene(const Scene& scene, float time);
  ~GpuScene();
  GpuScene(const GpuScene&) = delete;
  GpuScene& operator=(const GpuScene&) = delete;

  // Re-uploads the vertices at `time` (the frames of an animation; materials,
  // textures and lights stay). `scene` must be the one it was made from.
  void setTime(const Scene& scene, float time);
  // Replaces the lights (the scene's delta lights plus the spot lights of a
  // sample's emitter point, SceneResources::beginSample). A changed count
  // makes a new buffer: a program must bind() again.
  void setLights(const std::vector<Light>& lights);

  // Binds SSBOs, textures and the environment uniforms of `program`.
  void bind(ShaderLibrary& shaders, unsigned program) const;
  // The vertex buffer as an SSBO at BINDING_SCENE_VERTICES (SCENE_VERTEX_FLOATS per corner).
  void bindVertices() const;
  void draw() const;                        // all triangles; gl_PrimitiveID = triangle index
  void drawInstanced(int instances) const;  // the same, `instances` times (gl_InstanceID)

  size_t triangleCount() const { return triangles_; }
  const Bounds& bounds() const { return bounds_; }

 private:
  unsigned vao_ = 0, vbo_ = 0, materials_ = 0, triMaterial_ = 0, lights_ = 0;
  size_t lightCount_ = 0;
  unsigned albedoArray_ = 0, envMap_ = 0;
  size_t triangles_ = 0;
  Bounds bounds_, staticBounds_;  // all meshes at the last time; the static ones
  FlatScene flat_;                // setTime's buffers, kept between frames
  std::vector<float> verts_;
  glm::vec4 envColorScale_{0.0f};
  bool envHasMap_ = false;
};

}  // namespace vgi
