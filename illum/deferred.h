// Building blocks the GL modules share: the camera of a (jittered) frame, the
// G-buffer, the deferred direct-lighting pass and reading back an
// accumulation image. `direct` is these alone; the GI modules add to them.
#pragma once
#include <glm/glm.hpp>

#include "core/image.h"
#include "core/scene.h"

namespace vgi {

class GpuScene;
class LightMaps;
class ShaderLibrary;

// Halton radical inverse (sub-pixel jitter, frame rotations).
float halton(int index, int base);

struct FrameCamera {
  glm::mat4 viewProj, invViewProj;
  glm::vec3 position;
};
// Frame `frame` of `frames` jittered frames: frame 0 of 1 at pixel centres,
// otherwise Halton (2,3) offsets in [−½, ½)² pixels.
FrameCamera frameCamera(const Camera& camera, const Bounds& bounds, int width, int height, int frame, int frames);

// Position (w = 1 where a surface was seen), normal facing the viewer (w =
// material index), albedo and the geometric normal, at the texture units of
// shaders/shared/gbuffer.glsl when bound.
class GBuffer {
 public:
  GBuffer(int width, int height, ShaderLibrary& shaders);
  ~GBuffer();
  GBuffer(const GBuffer&) = delete;
  GBuffer& operator=(const GBuffer&) = delete;
  void render(const GpuScene& gpu, const FrameCamera& camera);
  void bind() const;  // at the units of shaders/shared/gbuffer.glsl
  int width() const { return w_; }
  int height() const { return h_; }

 private:
  int w_, h_;
  unsigned tex_[4] = {0, 0, 0, 0}, depth_ = 0, fbo_ = 0, prog_ = 0;
};

// An RGBA32F image that frames are added into (w counts the frames).
class Accumulator {
 public:
  Accumulator(int width, int height);
  ~Accumulator();
  Accumulator(const Accumulator&) = delete;
  Accumulator& operator=(const Accumulator&) = delete;
  unsigned texture() const { return tex_; }
  void clear() const;
  Image read() const;  // rgb / w, rows top-down

 private:
  int w_, h_;
  unsigned tex_ = 0;
};

// Deferred direct lighting (emission + delta lights through the light maps;
// environment behind), added into an accumulator: the `direct` module's frame.
class DirectPass {
 public:
  DirectPass(ShaderLibrary& shaders, const GpuScene& gpu, float shadowBias, float normalOffset);
  void shade(const GBuffer& gbuffer, const LightMaps& maps, const FrameCamera& camera, const Accumulator& target);

 private:
  const GpuScene& gpu_;
  unsigned prog_ = 0;
};

}  // namespace vgi
