#include "illum/framework/temporal.h"

#include <glad/gl.h>

#include "core/error.h"
#include "core/shader_library.h"
#include "illum/framework/deferred.h"
#include "illum/framework/sample_loop.h"
#include "shaders/illum/temporal/params.glsl"
#include "shaders/shared/bindings.glsl"

namespace vgi {

namespace {
// The cosine of the largest angle between a history texel's normal and the pixel's (≈ 25°), and how
// far (in pixel sizes at the pixel's distance) its surface may lie off the pixel's tangent plane: the
// G-buffers of two frames are jittered by up to a pixel, and a plane seen at a slant moves further.
constexpr float kNormalCos = 0.9f;
constexpr float kPlaneTolerance = 4.0f;
}  // namespace

TemporalFilter::TemporalFilter(int w, int h, const std::vector<std::string>& channels, ShaderLibrary& shaders)
    : w_(w), h_(h) {
  for (auto& c : channels) {
    Channel ch;
    for (GlTexture& t : ch.image) t = makeTexture2D(w_, h_, GL_RGBA32F);
    channels_.emplace(c, std::move(ch));
  }
  for (int i = 0; i < 2; ++i) {
    position_[i] = makeTexture2D(w_, h_, GL_RGBA32F);
    normal_[i] = makeTexture2D(w_, h_, GL_RGBA32F);
  }
  prog_ = shaders.program({"illum/temporal/resolve.comp.glsl"});
  checkBlockLayout(prog_, "Pass", sizeof(shared::TemporalParams), "illum/temporal/resolve.comp.glsl");
  params_ = std::make_unique<UniformBuffer>(sizeof(shared::TemporalParams));
}

void TemporalFilter::resolve(const GlFilm& film, const GBuffer& gbuffer, int samples,
                             const FrameCamera& camera, float pixelSize, const TemporalSettings& s,
                             bool hasHistory, bool newFrame, float currentFrames) {
  VGI_CHECK(samples > 0 && currentFrames > 0.0f && gbuffer.width() == w_ && gbuffer.height() == h_);
  if (newFrame) {
    // This frame's surfaces, for this resolve and the next frame's: kept at its sample 0, or the
    // G-buffer's now (rasterized: ordered before the copy).
    if (!kept_) copySurfaces(gbuffer, 1 - out_);
    kept_ = false;
    history_ = out_;
    out_ = 1 - history_;
    viewProj_[out_] = camera.viewProj;
  }
  static_assert(sizeof(shared::TemporalParams) % 16 == 0, "std140: padded to 16 bytes");
  shared::TemporalParams p{};
  for (int c = 0; c < 4; ++c) {
    p.viewProj[c] = camera.viewProj[c];
    p.previousViewProj[c] = viewProj_[history_][c];
  }
  p.eye = glm::vec4(camera.position, pixelSize);
  p.invSamples = 1.0f / float(samples);
  p.alpha = s.alpha;
  p.clampSigma = s.clampSigma;
  p.hasHistory = hasHistory ? 1 : 0;
  p.planeTolerance = kPlaneTolerance;
  p.normalCos = kNormalCos;
  p.cameraStill = hasHistory && camera.viewProj == viewProj_[history_] ? 1 : 0;
  p.currentFrames = currentFrames;
  params_->upload(&p);
  glUseProgram(prog_);
  params_->bind(UBO_PASS);
  // The current surfaces are this frame's copy (the G-buffer may hold a later, jittered sample's).
  glBindTextureUnit(TEXUNIT_GBUFFER_POSITION, position_[out_].get());
  glBindTextureUnit(TEXUNIT_GBUFFER_NORMAL, normal_[out_].get());
  glBindTextureUnit(TEXUNIT_PASS_INPUT, position_[history_].get());
  glBindTextureUnit(TEXUNIT_PASS_INPUT2, normal_[history_].get());
  for (auto& [name, c] : channels_) {
    glBindImageTexture(IMAGE_TEMPORAL_SUM, film.sumTexture(name), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
    glBindImageTexture(IMAGE_TEMPORAL_HISTORY, c.image[history_].get(), 0, GL_FALSE, 0, GL_READ_ONLY,
                       GL_RGBA32F);
    glBindImageTexture(IMAGE_TEMPORAL_OUTPUT, c.image[out_].get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glDispatchCompute(unsigned(w_ + 7) / 8, unsigned(h_ + 7) / 8, 1);
  }
  // Read back, or read as the next frame's history (images, fetches), or overwritten by the next
  // frame's G-buffer copy (a transfer): each after these dispatches.
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                  GL_TEXTURE_UPDATE_BARRIER_BIT);
}

void TemporalFilter::copySurfaces(const GBuffer& gbuffer, int slot) {
  VGI_CHECK(gbuffer.width() == w_ && gbuffer.height() == h_);
  glCopyImageSubData(gbuffer.texture(0), GL_TEXTURE_2D, 0, 0, 0, 0, position_[slot].get(), GL_TEXTURE_2D, 0,
                     0, 0, 0, w_, h_, 1);
  glCopyImageSubData(gbuffer.texture(1), GL_TEXTURE_2D, 0, 0, 0, 0, normal_[slot].get(), GL_TEXTURE_2D, 0, 0,
                     0, 0, w_, h_, 1);
}

void TemporalFilter::keepSurfaces(const GBuffer& gbuffer) {
  copySurfaces(gbuffer, 1 - out_);
  kept_ = true;
}

Image TemporalFilter::read(const std::string& channel) const {
  auto it = channels_.find(channel);
  VGI_CHECK(it != channels_.end());
  return readTexture(it->second.image[out_].get(), w_, h_, 1.0f);
}

double TemporalFilter::bytes() const {
  return double(w_) * double(h_) * 16.0 * double(2 * channels_.size() + 4);
}

}  // namespace vgi
