#include "illum/framework/sample_loop.h"

#include <glad/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>

#include "core/error.h"
#include "core/gpu_scene.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/shader_library.h"
#include "shaders/shared/bindings.glsl"

namespace vgi {

// ---- GlFilm

GlFilm::GlFilm(int width, int height, const std::vector<std::string>& channels, ShaderLibrary& shaders)
    : w_(width), h_(height), shaders_(shaders) {
  for (auto& c : channels) {
    Channel ch;
    ch.sample = makeTexture2D(w_, h_, GL_RGBA32F);
    ch.sum = makeTexture2D(w_, h_, GL_RGBA32F);
    ch.compensation = makeTexture2D(w_, h_, GL_RGBA32F);
    channels_.emplace(c, std::move(ch));
  }
  prog_ = shaders.program({"illum/accumulate.comp.glsl"});
  clear();
}

void GlFilm::clear() {
  const float zero[4] = {0, 0, 0, 0};
  for (auto& [name, c] : channels_) {
    glClearTexImage(c.sample.get(), 0, GL_RGBA, GL_FLOAT, zero);
    glClearTexImage(c.sum.get(), 0, GL_RGBA, GL_FLOAT, zero);
    glClearTexImage(c.compensation.get(), 0, GL_RGBA, GL_FLOAT, zero);
  }
}

unsigned GlFilm::sampleImage(const std::string& channel) const {
  auto it = channels_.find(channel);
  if (it == channels_.end())
    fail("internal: the film has no channel '", channel, "' (an output not asked for)");
  return it->second.sample.get();
}

void GlFilm::accumulate(Accumulation mode) {
  glUseProgram(prog_);
  shaders_.setUniform(prog_, "uCompensated", mode == Accumulation::Compensated ? 1 : 0);
  for (auto& [name, c] : channels_) {
    glBindImageTexture(IMAGE_ACCUMULATE_SAMPLE, c.sample.get(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
    glBindImageTexture(IMAGE_ACCUMULATE_SUM, c.sum.get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    glBindImageTexture(IMAGE_ACCUMULATE_COMPENSATION, c.compensation.get(), 0, GL_FALSE, 0, GL_READ_WRITE,
                       GL_RGBA32F);
    glDispatchCompute(unsigned(w_ + 7) / 8, unsigned(h_ + 7) / 8, 1);
  }
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                  GL_TEXTURE_UPDATE_BARRIER_BIT);
}

Image GlFilm::read(const std::string& channel, int samples) const {
  return readTexture(sumTexture(channel), w_, h_, samples > 0 ? 1.0f / float(samples) : 0.0f);
}

unsigned GlFilm::sumTexture(const std::string& channel) const {
  auto it = channels_.find(channel);
  VGI_CHECK(it != channels_.end());
  return it->second.sum.get();
}

Image readTexture(unsigned texture, int w, int h, float scale) {
  std::vector<glm::vec4> px(size_t(w) * h);
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(px.size() * sizeof(glm::vec4)), px.data());
  Image image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      image.at(x, y) = glm::vec3(px[size_t(h - 1 - y) * w + x]) * scale;  // GL rows start at the bottom
  return image;
}

// ---- CpuFilm

CpuFilm::CpuFilm(int width, int height, const std::vector<std::string>& channels) : w_(width), h_(height) {
  for (auto& c : channels) {
    Channel ch;
    ch.sample.assign(size_t(w_) * h_, glm::vec3(0.0f));
    ch.sum.assign(size_t(w_) * h_, glm::dvec3(0.0));
    channels_.emplace(c, std::move(ch));
  }
}

void CpuFilm::clear() {
  for (auto& [name, c] : channels_) {
    std::fill(c.sample.begin(), c.sample.end(), glm::vec3(0.0f));
    std::fill(c.sum.begin(), c.sum.end(), glm::dvec3(0.0));
  }
}

glm::vec3* CpuFilm::samplePixels(const std::string& channel) {
  auto it = channels_.find(channel);
  if (it == channels_.end())
    fail("internal: the film has no channel '", channel, "' (an output not asked for)");
  return it->second.sample.data();
}

void CpuFilm::accumulate(int threads) {
  for (auto& [name, c] : channels_)
    parallelFor(c.sum.size(), 1 << 14, threads, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) c.sum[i] += glm::dvec3(c.sample[i]);
    });
}

Image CpuFilm::read(const std::string& channel, int samples) const {
  auto it = channels_.find(channel);
  VGI_CHECK(it != channels_.end());
  Image image(w_, h_);
  if (samples > 0)
    for (size_t i = 0; i < image.pixels.size(); ++i)
      image.pixels[i] = glm::vec3(it->second.sum[i] / double(samples));
  return image;
}

// ---- SampleTargets

void SampleTargets::prepare(const RenderRequest& req, bool gl, bool gbuffer, ShaderLibrary* shaders) {
  std::vector<std::string> channels = {"image"};
  for (auto& a : req.aovs) channels.push_back(a);
  const bool same = w_ == req.width && h_ == req.height && channels == channels_ && bool(gbuffer_) == gbuffer;
  if (same && (gl ? bool(glFilm_) : bool(cpuFilm_))) {
    if (glFilm_) glFilm_->clear();
    if (cpuFilm_) cpuFilm_->clear();
    return;
  }
  gbuffer_.reset();
  glFilm_.reset();
  cpuFilm_.reset();
  temporal_.reset();
  w_ = req.width;
  h_ = req.height;
  channels_ = channels;
  if (gl) {
    VGI_CHECK(shaders);
    if (gbuffer) gbuffer_ = std::make_unique<GBuffer>(w_, h_, *shaders);
    glFilm_ = std::make_unique<GlFilm>(w_, h_, channels, *shaders);
  } else {
    cpuFilm_ = std::make_unique<CpuFilm>(w_, h_, channels);
  }
}

namespace {
size_t scratchTexelBytes(unsigned format) {
  switch (format) {
    case GL_RGBA32F:
      return 16;
    case GL_RGBA16F:
      return 8;
    case GL_R32F:
    case GL_R32UI:
    case GL_RGBA8:
      return 4;
    default:
      fail("scratch texture format 0x", std::hex, format, " has no size here (SampleTargets::bytes)");
  }
}
}  // namespace

double SampleTargets::bytes() const {
  const double pixels = double(w_) * double(h_), channels = double(channels_.size());
  double b = 0;
  if (gbuffer_) b += pixels * (4 * 16 + 4);
  if (glFilm_) b += pixels * channels * 3 * 16;
  if (cpuFilm_) b += pixels * channels * (12 + 24);
  for (auto& [name, s] : scratch_) b += double(s.w) * double(s.h) * double(scratchTexelBytes(s.format));
  if (temporal_) b += temporal_->bytes();
  return b;
}

TemporalFilter& SampleTargets::temporal(ShaderLibrary& shaders) {
  VGI_CHECK(gbuffer_ && glFilm_);
  if (!temporal_) temporal_ = std::make_unique<TemporalFilter>(w_, h_, channels_, shaders);
  return *temporal_;
}

unsigned SampleTargets::scratchTexture(const std::string& name, int width, int height, unsigned format) {
  scratchTexelBytes(format);  // a format bytes() can count
  Scratch& s = scratch_[name];
  if (!s.texture || s.w != width || s.h != height || s.format != format) {
    s.texture = makeTexture2D(width, height, format);
    s.w = width;
    s.h = height;
    s.format = format;
  }
  return s.texture.get();
}

// ---- Frame

ShaderLibrary& Frame::shaders() const {
  if (!shaders_) fail("internal: a CPU method asked for the shader library");
  return *shaders_;
}

GBuffer& Frame::gbuffer() const {
  if (!targets_.gbuffer()) fail("internal: method '", request.method, "' read a G-buffer it did not declare");
  return *targets_.gbuffer();
}

unsigned Frame::sampleImage(const std::string& channel) const {
  if (!targets_.glFilm()) fail("internal: a CPU method asked for a GL sample image");
  return targets_.glFilm()->sampleImage(channel);
}

glm::vec3* Frame::samplePixels(const std::string& channel) const {
  if (!targets_.cpuFilm()) fail("internal: a GL method asked for CPU sample pixels");
  return targets_.cpuFilm()->samplePixels(channel);
}

// ---- the loop

namespace {
std::map<std::string, long> callCounts(const Profiler& p) {
  std::map<std::string, long> m;
  const nlohmann::json counts = p.callCounts();  // items() must not outlive its object
  for (auto& [k, v] : counts.items()) m[k] = v.get<long>();
  return m;
}
}  // namespace

namespace {
const RenderRequest& checkedRequest(const RenderRequest& req) {
  VGI_CHECK(req.scene);
  return req;
}
}  // namespace

SampleSession::SampleSession(Method& method, const RenderRequest& req, SceneResources& res,
                             SampleTargets& targets, ShaderLibrary* shaders, Profiler& prof)
    : method_(method),
      req_(req),
      res_(res),
      targets_(targets),
      shaders_(shaders),
      prof_(prof),
      frame_(checkedRequest(req), res, targets, shaders, prof, extra_) {
  res_.update(req_.time, prof_);
  targets_.prepare(req_, shaders_ != nullptr, res_.needs().gbuffer, shaders_);
  method_.prepareFrame(frame_);
  // The passes timed from here on are the per-sample passes (the read-back
  // of a checkpoint is not one).
  before_ = callCounts(prof_);
}

FrameCamera SampleSession::camera(int k) const {
  return frameCamera(req_.scene->cameraAt(req_.time),
                     res_.needs().gbuffer ? res_.get<GpuScene>().bounds() : req_.scene->bounds(req_.time),
                     req_.width, req_.height, k);
}

bool SampleSession::addSample() {
  const bool gl = shaders_ != nullptr;
  const int k = req_.firstSample + done_;
  if (gl) {
    frame_.camera = camera(k);
    if (res_.needs().gbuffer) {
      auto s = prof_.scope("gbuffer");
      targets_.gbuffer()->render(res_.get<GpuScene>(), frame_.camera);
      // Sample 0 is at the pixel centres: the temporal filter keeps its surfaces (filter draws none).
      if (k == 0 && temporalApplies()) targets_.temporal(*shaders_).keepSurfaces(*targets_.gbuffer());
    }
  }
  res_.beginSample(k, req_.seed, prof_);
  if (!method_.addSample(frame_, k)) return false;  // stopped inside the sample: not counted
  filtered_ = false;
  {
    auto s = prof_.scope("accumulate");
    if (gl)
      targets_.glFilm()->accumulate(req_.accumulation);
    else
      targets_.cpuFilm()->accumulate(req_.threads);
  }
  if (gl) prof_.resolve(false);
  ++done_;
  return true;
}

Image SampleSession::read(const std::string& channel) const {
  auto s = prof_.scope("readback");
  if (filtered_) return targets_.temporal()->read(channel);
  return shaders_ ? targets_.glFilm()->read(channel, done_) : targets_.cpuFilm()->read(channel, done_);
}

// `built` is what the resources allocated; the per-sample passes are those timed since the constructor.
void SampleSession::describe(RenderResult& r) const {
  const std::map<std::string, long> after = callCounts(prof_);
  for (auto& [name, n] : after) {
    auto b = before_.find(name);
    if (name != "readback" && n > (b == before_.end() ? 0 : b->second)) r.samplePasses.push_back(name);
  }
  if (targets_.gbuffer()) r.built.push_back("gbuffer");
  for (auto& b : res_.built()) r.built.push_back(b);
}

RenderResult SampleSession::sofar() const {
  RenderResult r;
  r.sppCompleted = done_;
  describe(r);
  r.image = read("image");
  for (auto& a : req_.aovs) r.aovs[a] = read(a);
  return r;
}

bool SampleSession::temporalApplies() const {
  return method_.temporal().on && req_.temporal && shaders_ && targets_.gbuffer();
}

bool SampleSession::filter(float currentFrames) {
  const TemporalSettings temporal = method_.temporal();
  if (!temporalApplies() || done_ == 0) return false;
  if (filteredBefore_ && currentFrames * temporal.alpha >= 1.0f) return false;  // the mean itself
  auto s = prof_.scope("temporal");
  const Camera cam = req_.scene->cameraAt(req_.time);
  const float pixelSize = 2.0f * std::tan(0.5f * glm::radians(cam.fovYDeg)) / float(req_.height);
  // The surfaces at the pixels' centres (sample 0's camera), the same in every frame where nothing
  // moves: a jittered G-buffer's edge pixels would see another surface from frame to frame.
  const FrameCamera centre = camera(0);
  // (Kept at sample 0 when this frame drew it; else drawn here.)
  TemporalFilter& tf = targets_.temporal(*shaders_);
  if (!tf.hasSurfaces(!filteredBefore_)) targets_.gbuffer()->render(res_.get<GpuScene>(), centre);
  tf.resolve(*targets_.glFilm(), *targets_.gbuffer(), done_, centre, pixelSize, temporal, req_.frame > 0,
             !filteredBefore_, currentFrames);
  filteredBefore_ = filtered_ = true;
  return true;
}

RenderResult SampleSession::finish() {
  if (!filteredBefore_) filter(1.0f);
  RenderResult r = sofar();
  r.interrupted = done_ < req_.spp;
  method_.finishFrame(frame_);
  r.extra = extra_;
  res_.addStats(r.extra);
  return r;
}

RenderResult renderFrame(Method& method, const RenderRequest& req, SceneResources& res,
                         SampleTargets& targets, ShaderLibrary* shaders, Profiler& prof) {
  const auto start = std::chrono::steady_clock::now();
  SampleSession session(method, req, res, targets, shaders, prof);
  std::set<int> checkpoints(req.checkpoints.begin(), req.checkpoints.end());
  ProgressBar bar(req.method.empty() ? "render" : req.method, req.spp);
  bool timeLimited = false;
  while (session.samples() < req.spp && !interruptRequested()) {
    if (!session.addSample()) break;
    const int done = session.samples();
    if (req.progress) bar.advance();
    if (req.onCheckpoint && checkpoints.count(done) && done < req.spp)
      req.onCheckpoint(session.sofar(), prof);
    if (req.timeLimitS > 0 && done < req.spp) {
      if (shaders) glFinish();  // the wall time of work queued, not of work submitted
      if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >= req.timeLimitS) {
        timeLimited = true;
        break;
      }
    }
  }
  bar.finish();
  RenderResult result = session.finish();
  result.timeLimited = timeLimited;
  result.interrupted = result.interrupted && !timeLimited;
  return result;
}

RenderResult renderStill(Method& method, const RenderRequest& req, Profiler& prof, GlContext* gl,
                         ShaderLibrary* shaders) {
  const SceneNeeds needs = method.needs();
  needs.check(req.method.empty() ? "method" : req.method, shaders != nullptr);
  SceneResources resources(*req.scene, needs, gl, shaders, {req.time}, req.threads);
  SampleTargets targets;
  return renderFrame(method, req, resources, targets, shaders, prof);
}

void bindSampleAndSplitImages(const Frame& f) {
  const unsigned sample = f.sampleImage("image");
  glBindImageTexture(IMAGE_SAMPLE, sample, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  const unsigned indirect = f.wants("indirect") ? f.sampleImage("indirect") : sample;
  const unsigned direct = f.wants("direct") ? f.sampleImage("direct") : sample;
  glBindImageTexture(IMAGE_SAMPLE_AOV0, indirect, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glBindImageTexture(IMAGE_SAMPLE_AOV1, direct, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
}

}  // namespace vgi
