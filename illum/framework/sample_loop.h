// The framework's sample loop: one implementation of what every method's
// frame needs around its own passes. Per frame: the scene resources made
// current (SceneResources::update), the render targets kept or made at the
// image size, Method::prepareFrame; per sample k: the jittered camera and, for
// methods that need it, the G-buffer; Method::addSample(k); accumulation of
// the sample's channels (compensated or plain, see Accumulation); the GPU
// timers resolved; progress; Ctrl-C; checkpoints. Then the read-back of the
// image and the outputs asked for, and the stats: `built` from what the
// resources allocated, `samplePasses` from the passes timed inside the loop.
#pragma once
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/gl_handles.h"
#include "illum/framework/deferred.h"
#include "illum/framework/method.h"
#include "illum/framework/temporal.h"

namespace vgi {

class GlContext;
class ShaderLibrary;

// Accumulates samples of named channels ("image", outputs) on the GPU: each
// channel has a sample image (RGBA32F, GL rows bottom-up) the method writes,
// and a sum (+ Kahan compensation) the loop adds it into.
class GlFilm {
 public:
  GlFilm(int width, int height, const std::vector<std::string>& channels, ShaderLibrary& shaders);
  void clear();
  unsigned sampleImage(const std::string& channel) const;
  // sum += sample for every channel (shaders/illum/accumulate.comp.glsl).
  void accumulate(Accumulation mode);
  Image read(const std::string& channel, int samples) const;  // sum / samples, rows top-down
  unsigned sumTexture(const std::string& channel) const;

 private:
  struct Channel {
    GlTexture sample, sum, compensation;
  };
  int w_, h_;
  std::map<std::string, Channel> channels_;
  unsigned prog_ = 0;
  ShaderLibrary& shaders_;
};

// An RGBA32F texture's rgb × scale (GL rows bottom-up) as an image (rows top-down).
Image readTexture(unsigned texture, int width, int height, float scale);

// The same on the CPU: the method writes samplePixels (rows top-down), sums are doubles.
class CpuFilm {
 public:
  CpuFilm(int width, int height, const std::vector<std::string>& channels);
  void clear();
  glm::vec3* samplePixels(const std::string& channel);
  void accumulate(int threads);
  Image read(const std::string& channel, int samples) const;

 private:
  struct Channel {
    std::vector<glm::vec3> sample;
    std::vector<glm::dvec3> sum;
  };
  int w_, h_;
  std::map<std::string, Channel> channels_;
};

// What the loop keeps between the frames of a run: the G-buffer, the film,
// the temporal filter's history, and the methods' scratch textures (kept while their size holds).
class SampleTargets {
 public:
  SampleTargets() = default;
  SampleTargets(const SampleTargets&) = delete;
  SampleTargets& operator=(const SampleTargets&) = delete;

  // Makes the targets for this request (same size and channels: kept, film cleared).
  void prepare(const RenderRequest& req, bool gl, bool gbuffer, ShaderLibrary* shaders);
  GBuffer* gbuffer() { return gbuffer_.get(); }
  GlFilm* glFilm() { return glFilm_.get(); }
  CpuFilm* cpuFilm() { return cpuFilm_.get(); }
  // The temporal filter of these targets (GL, with a G-buffer), made at the first call.
  TemporalFilter& temporal(ShaderLibrary& shaders);
  const TemporalFilter* temporal() const { return temporal_.get(); }
  // A 2D texture of one level, nearest filtering, kept across frames under `name` (RGBA32F, RGBA16F,
  // R32F or RGBA8).
  unsigned scratchTexture(const std::string& name, int width, int height, unsigned internalFormat);
  // What the targets hold: the G-buffer (four RGBA32F + 32-bit depth per pixel), the film (GL: sample,
  // sum and compensation RGBA32F per channel; CPU: float sample and double sum) and the scratch
  // textures and the temporal filter's history — the stats' memory `targets_bytes`.
  double bytes() const;

 private:
  struct Scratch {
    GlTexture texture;
    int w = 0, h = 0;
    unsigned format = 0;
  };
  int w_ = 0, h_ = 0;
  std::vector<std::string> channels_;
  std::unique_ptr<GBuffer> gbuffer_;
  std::unique_ptr<GlFilm> glFilm_;
  std::unique_ptr<CpuFilm> cpuFilm_;
  std::unique_ptr<TemporalFilter> temporal_;
  std::map<std::string, Scratch> scratch_;
};

// What a method sees of the frame it renders.
class Frame {
 public:
  Frame(const RenderRequest& request, SceneResources& resources, SampleTargets& targets,
        ShaderLibrary* shaders, Profiler& profiler, nlohmann::json& extra)
      : request(request),
        scene(*request.scene),
        resources(resources),
        profiler(profiler),
        extra(extra),
        targets_(targets),
        shaders_(shaders) {}

  const RenderRequest& request;
  const Scene& scene;
  SceneResources& resources;
  Profiler& profiler;
  nlohmann::json& extra;  // the method's stats (RenderResult::extra)
  FrameCamera camera{};   // GL: this sample's jittered camera (set by the loop before addSample)

  int width() const { return request.width; }
  int height() const { return request.height; }
  bool wants(const std::string& output) const { return request.wants(output); }
  ShaderLibrary& shaders() const;
  GBuffer& gbuffer() const;  // after the loop rendered it for this sample
  // GL: the RGBA32F image the sample of `channel` ("image" or an output asked for) is written to.
  unsigned sampleImage(const std::string& channel) const;
  unsigned scratchTexture(const std::string& name, int width, int height, unsigned internalFormat) const {
    return targets_.scratchTexture(name, width, height, internalFormat);
  }
  // CPU: the W×H pixels (rows top-down) of the sample of `channel`.
  glm::vec3* samplePixels(const std::string& channel) const;
  // Counts `bytes` the method keeps across frames outside the shared resources (its own buffers and
  // textures) into extra's "state_bytes", which the stats' memory reports (RenderJob::memory); call
  // it from finishFrame.
  void addStateBytes(double bytes) const { extra["state_bytes"] = extra.value("state_bytes", 0.0) + bytes; }

 private:
  SampleTargets& targets_;
  ShaderLibrary* shaders_;
};

// Binds the frame's sample image ("image", read-write) at IMAGE_SAMPLE and the
// "indirect" / "direct" outputs at IMAGE_SAMPLE_AOV0 / AOV1 (shared/bindings.glsl)
// for a pass that composes the sample and splits it; an output not asked for
// gets the sample image (the pass must not write it: uWriteIndirect/uWriteDirect).
void bindSampleAndSplitImages(const Frame& f);

// The loop of one frame, a sample at a time, for a caller that decides when
// to stop (renderFrame; the viewer, which shows the image after each sample
// and starts a new session when the camera or a parameter changes). The
// constructor makes the resources current, prepares the targets (the film
// cleared) and the method; the request must outlive the session.
class SampleSession {
 public:
  SampleSession(Method& method, const RenderRequest& request, SceneResources& resources,
                SampleTargets& targets, ShaderLibrary* shaders, Profiler& profiler);
  SampleSession(const SampleSession&) = delete;
  SampleSession& operator=(const SampleSession&) = delete;
  // Renders and accumulates sample samples() (the jittered camera of
  // request.spp samples); false if the method stopped inside it (Ctrl-C: not counted).
  bool addSample();
  int samples() const { return done_; }
  // The mean of the samples so far of "image" or an output asked for (rows top-down); after finish()
  // of a frame the method filters over time, the filtered image.
  Image read(const std::string& channel) const;
  // Where the request allows it (RenderRequest::temporal) and the method filters over time
  // (Method::temporal): filters the samples so far with the history (the session's first call starts
  // a new frame of it; later calls refine that frame, its samples counting as `currentFrames` frames)
  // and read() answers the filtered image until the next sample. False (nothing done) otherwise, or
  // once a refining call would give the mean itself (samples ≥ 1/alpha: read() is the mean).
  bool filter(float currentFrames);
  bool filtered() const { return filtered_; }
  // The method's temporal filter runs on this session's frames (on, an animation's or the viewer's, GL).
  bool temporalApplies() const;
  // The result with the samples so far: images, stats, `built`, `samplePasses`. A frame of an
  // animation is filtered first (filter(1), unless the session filtered already).
  RenderResult finish();
  // The result so far without finishing the frame (a checkpoint).
  RenderResult sofar() const;

 private:
  void describe(RenderResult& r) const;
  FrameCamera camera(int k) const;  // the camera of sample k (k = 0: no jitter)
  Method& method_;
  const RenderRequest& req_;
  SceneResources& res_;
  SampleTargets& targets_;
  ShaderLibrary* shaders_;
  Profiler& prof_;
  nlohmann::json extra_ = nlohmann::json::object();
  Frame frame_;
  std::map<std::string, long> before_;
  int done_ = 0;
  bool filtered_ = false;        // read() answers the temporal filter's images
  bool filteredBefore_ = false;  // the session started its frame of the filter's history
};

// One frame of `method`: the loop described at the top. `shaders` is set for GL methods.
RenderResult renderFrame(Method& method, const RenderRequest& request, SceneResources& resources,
                         SampleTargets& targets, ShaderLibrary* shaders, Profiler& profiler);
// A still of `method` with resources and targets of its own (tests, tools);
// gl and shaders are set for a GL method (its context current).
RenderResult renderStill(Method& method, const RenderRequest& request, Profiler& profiler,
                         GlContext* gl = nullptr, ShaderLibrary* shaders = nullptr);

}  // namespace vgi
