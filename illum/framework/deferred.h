// Building blocks of every GL frame: the camera of a (jittered) frame and the G-buffer. (The deferred
// direct-lighting pass is a kit: illum/kits/direct_pass.h; accumulation is the sample loop's:
// illum/framework/sample_loop.h.)
#pragma once
#include <glm/glm.hpp>

#include "core/gl_handles.h"
#include "core/image.h"
#include "core/scene.h"

namespace vgi {

class GpuScene;
class ShaderLibrary;

// Halton radical inverse (sub-pixel jitter, frame rotations).
float halton(int index, int base);

struct FrameCamera {
  glm::mat4 viewProj, invViewProj;
  glm::vec3 position;
  glm::vec3 forward;      // the view axis (unit)
  float clipNear = 0.0f;  // > 0: the camera's cut-away distance (Camera::clipNear), the near plane
};
// Jittered frame `frame`: frame 0 at pixel centres, frame k > 0 at Halton
// (2,3) point k + 1, an offset in [−½, ½)² pixels. A frame's jitter does not
// depend on how many frames follow, so the first k samples of any run are the
// same k samples (the viewer's screenshot after k frames is `vgi render --spp k`).
FrameCamera frameCamera(const Camera& camera, const Bounds& bounds, int width, int height, int frame);

// The exact methods' pinhole camera (reference, reference_gl): the ray through
// image point (x, y) (pixels, rows top-down) is normalize(fwd + px·right + py·up)
// with px = (2x/W − 1)·tanHalf·aspect, py = (1 − 2y/H)·tanHalf. Built from the
// camera's own vectors, not by inverting a projection (whose near-plane points
// lose the direction's precision: a pixel's worth at 128²).
struct PinholeView {
  glm::vec3 position, fwd, right, up;
  float tanHalf, aspect;
  float clipNear = 0.0f;  // Camera::clipNear
  // Where the camera ray along unit direction d starts: the eye, or with a cut-away distance the
  // ray's point on the near plane (what lies before it is not seen).
  glm::vec3 origin(glm::vec3 d) const {
    return clipNear > 0.0f ? position + d * (clipNear / glm::dot(d, fwd)) : position;
  }
};
PinholeView pinholeView(const Camera& camera, int width, int height);

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
  // Channel c (0 position, 1 normal, 2 albedo, 3 geometric normal; RGBA32F, rows bottom-up).
  unsigned texture(int c) const { return tex_[c].get(); }
  int width() const { return w_; }
  int height() const { return h_; }

 private:
  int w_, h_;
  ShaderLibrary& shaders_;
  GlTexture tex_[4];
  unsigned depth_ = 0, fbo_ = 0, prog_ = 0;
};

}  // namespace vgi
