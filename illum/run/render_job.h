// One render as `vgi render` runs it: load the scene, resolve parameters
// (scene preset, then --set), create the method, make a GL context if the
// method needs one, render, and describe everything in a stats JSON.
#pragma once
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/gl_context.h"
#include "core/output_files.h"
#include "illum/framework/method.h"
#include "illum/framework/render_options.h"
#include "illum/framework/sample_loop.h"

namespace vgi {

struct RenderOutput {
  RenderResult result;
  nlohmann::json stats;
};

// Places point or spot light `index` at `position`; throws naming the index if there is no such light
// or it is directional.
void placeLight(std::vector<Light>& lights, int index, glm::vec3 position);
// Everything a RenderJob checks before it makes a GL context: the options, the scene with --camera
// and --light applied, the method's parameters, outputs (--aov) and needs. Throws naming the option
// and value. `vgi render --print-job` prints only a job this accepts.
void checkRenderJob(const RenderOptions& options);
// What a render is made of, built from its options: the scene (its camera
// replaced by --camera), the method with its parameters (preset, then --set),
// a GL context if the method needs one (or the caller's: the viewer's
// window), the scene resources and the sample targets. runRender drives it;
// the viewer keeps one, moves the scene's camera, and swaps the method.
class RenderJob {
 public:
  explicit RenderJob(const RenderOptions& options, GlContext* gl = nullptr);
  ~RenderJob();
  RenderJob(const RenderJob&) = delete;
  RenderJob& operator=(const RenderJob&) = delete;

  // Replaces the method (and its --set and outputs); everything is checked
  // before anything changes, so on an error the job keeps the old method.
  // The scene resources are kept when the new method needs the same ones.
  void setMethod(const std::string& name, const std::vector<std::string>& set,
                 const std::vector<std::string>& aovs);

  const RenderOptions& options() const { return opt_; }
  RenderOptions& options() { return opt_; }  // size, spp, seed, time: read by request()
  Scene& scene() { return scene_; }
  const Scene& scene() const { return scene_; }
  const MethodInfo& info() const { return *info_; }
  Method& method() { return *method_; }
  const ParamSet& params() const { return *params_; }
  SceneResources& resources() { return *resources_; }
  SampleTargets& targets() { return targets_; }
  ShaderLibrary* shaders() const;  // set for a GL method
  GlContext* gl() const;           // set for a GL method
  // The request of a still with these options (time = options().time).
  RenderRequest request() const;
  // The scene's lights changed (the viewer moved one): the resources re-derive what depends on
  // them (light maps, radiance) at the next update, and keep the rest (the grid, the pyramid).
  void lightsChanged();
  // The scene's keyframed lights at `time` (Scene::placeLightsAt), and lightsChanged(); nothing for a
  // scene without light paths. The still and the frame loops call it before each render.
  void placeLightsAt(float time);
  // The stats of the run (method, scene, size, camera, resolved parameters, GL renderer, revision, …).
  // Its "memory" (measured when called; a render measures again when done) holds what the process uses (core/gpu_memory.h), the same measured before any resource
  // was built ("baseline"), the bytes the resources, the method and the sample loop's targets report
  // ("resources_bytes", "method_bytes", "targets_bytes", "reported_bytes"), and how much the device's (GPU where GL reports it, else
  // resident) memory grew since the baseline against them ("growth_bytes", "growth_over_reported":
  // 1 = the reported bytes are what it costs).
  nlohmann::json describe() const;
  // Its "memory" alone, measured now; `extra` (a render's RenderResult::extra) gives the method's
  // "state_bytes".
  nlohmann::json memory(const nlohmann::json& extra = nlohmann::json()) const;
  // Throws if the GL context counted errors; throws if the result has a non-finite pixel.
  void checkGl() const;
  void checkFiniteResult(const RenderResult& result) const;

 private:
  std::vector<float> frameTimes() const;
  void makeResources(SceneNeeds needs);  // for the current method
  RenderOptions opt_;
  Scene scene_;
  std::unique_ptr<GlContext> ownGl_;
  GlContext* gl_ = nullptr;
  std::unique_ptr<ShaderLibrary> shaders_;
  const MethodInfo* info_ = nullptr;
  std::unique_ptr<ParamSet> params_;
  std::unique_ptr<Method> method_;
  std::unique_ptr<SceneResources> resources_;
  SampleTargets targets_;
  nlohmann::json baselineMemory_;  // measuredMemory once the scene and GL context exist, before any resource
};

// Renders a still (options.frames == 1: the returned output holds the image)
// or an animation: then `onFrame` receives each frame as it completes (its
// stats are the frame's: time, timings, extra) and the returned output holds
// the last frame's image and stats for the whole run, with a "frames" array.
// Ctrl-C stops an animation after the current frame.
// With checkpoints, `onCheckpoint` receives the image and its stats at each
// of those sample counts below --spp (the result is the last).
using FrameSink = std::function<void(int frame, const RenderOutput& output)>;
using CheckpointSink = std::function<void(int spp, const RenderOutput& output)>;
RenderOutput runRender(const RenderOptions& options, const FrameSink& onFrame = {},
                       const CheckpointSink& onCheckpoint = {});

// What one frame reports: samples, per-pass timings (GPU where measured),
// calls, the method's stats, what was built, the per-sample passes.
nlohmann::json renderStats(const RenderResult& result, const Profiler& profiler);

// The method's parameters as a render with these options would resolve them
// (scene-dependent defaults included), without rendering; `outputs`, when
// given, receives the extra outputs (AOVs) the method can write.
nlohmann::json resolveParameters(const RenderOptions& options, std::vector<std::string>* outputs = nullptr);

}  // namespace vgi
