// The sample loop's temporal filter: the frames of an animation blended with the previous frames'
// filtered image reprojected through the G-buffer (shaders/illum/temporal/resolve.comp.glsl says
// how: camera reprojection of the surface's world position, history rejected where the previous
// G-buffer saw another surface, clipped to the current frame's neighbourhood, an exponential average
// of at most 1 / alpha frames). A method turns it on with TemporalSettings (Method::temporal); the
// loop applies it at the end of every frame of an animation (the first has no history), and with
// continueSamples the animation continues its frames' sample sequences (frame f takes samples f·spp …).
#pragma once
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/gl_handles.h"
#include "core/image.h"
#include "illum/framework/compute_pass.h"
#include "illum/framework/method.h"

namespace vgi {

class GlFilm;
class GBuffer;
class ShaderLibrary;
struct FrameCamera;

class TemporalFilter {
 public:
  TemporalFilter(int width, int height, const std::vector<std::string>& channels, ShaderLibrary& shaders);
  // Filters the film's mean (its sum over `samples`) of every channel with the history (read when
  // `hasHistory`: not the first frame of a run); the result, this frame's G-buffer surfaces and
  // camera are the next frame's history. `newFrame`: the last result becomes the history (false: the
  // same frame again, with more samples, reads the history its first resolve read). The mean counts
  // as `currentFrames` frames. `camera` is this frame's camera without jitter, `pixelSize` a pixel's
  // size per unit distance.
  void resolve(const GlFilm& film, const GBuffer& gbuffer, int samples, const FrameCamera& camera,
               float pixelSize, const TemporalSettings& settings, bool hasHistory, bool newFrame,
               float currentFrames);
  // The G-buffer as drawn now (at the pixel centres: a frame's sample 0) is the next new frame's
  // surfaces: its resolve reads them instead of the G-buffer, which need not be drawn again.
  void keepSurfaces(const GBuffer& gbuffer);
  // Whether a resolve of a new frame (newFrame) or of the same frame again has its surfaces without
  // the G-buffer (keepSurfaces since the last new frame; the same frame's were kept by its first).
  bool hasSurfaces(bool newFrame) const { return !newFrame || kept_; }
  // The last resolve's image of `channel` (rows top-down).
  Image read(const std::string& channel) const;
  // Per frame of the two (the history, the one being filtered): an RGBA32F image per channel, the
  // G-buffer's position and normal.
  double bytes() const;

 private:
  struct Channel {
    GlTexture image[2];
  };
  int w_, h_;
  std::map<std::string, Channel> channels_;
  // Frame slot `out_` is being filtered, `history_` holds the frame before: its images, the G-buffer
  // surfaces at its pixel centres, its camera.
  int out_ = 0, history_ = 1;
  bool kept_ = false;  // slot 1 − out_ holds the next new frame's surfaces (keepSurfaces)
  GlTexture position_[2], normal_[2];
  glm::mat4 viewProj_[2] = {glm::mat4(1.0f), glm::mat4(1.0f)};
  void copySurfaces(const GBuffer& gbuffer, int slot);  // its position and normal into slot `slot`
  unsigned prog_ = 0;
  // Its shared::TemporalParams (shaders/illum/temporal/params.glsl, read by the .cpp only: an installed
  // header includes no shader but shaders/shared/).
  std::unique_ptr<UniformBuffer> params_;
};

}  // namespace vgi
