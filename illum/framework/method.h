// The interface every rendering method implements, and the explicit registry.
// A method reads its parameters from a ParamSet when it is created (unknown
// keys are errors) and from them declares its needs; the framework then
// renders frames of a scene with it, one sample at a time.
#pragma once
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/params.h"
#include "core/profiler.h"
#include "core/scene.h"
#include "illum/framework/resources.h"

namespace vgi {

class Frame;

enum class Accumulation {
  Compensated,  // Kahan summation of the samples on the GPU (10^5 samples do not drift); CPU: double sums
  Plain,        // one float add per sample (the pre-framework behaviour; drifts after ~10^4 samples)
};

// Whether the sample loop filters the frames of an animation over time, and how
// (illum/framework/temporal.h; a method's `temporal` parameters: illum/kits/shared_params.h).
struct TemporalSettings {
  bool on = false;
  float alpha = 0.1f;       // the least weight of a frame: history of at most 1 / alpha frames
  float clampSigma = 1.0f;  // the history clipped to mean ± clampSigma·σ of the current 3×3; 0: not
  // Frame f takes samples f·spp … (the history adds samples: lower static error) instead of the
  // same samples 0 … spp − 1 every frame (where nothing changes, the frames are equal: no flicker).
  bool continueSamples = false;
};

struct RenderRequest {
  const Scene* scene = nullptr;
  std::string method;  // its registry name (progress bar, messages)
  int width = 256, height = 256;
  int spp = 1;
  uint32_t seed = 0;
  int threads = 0;  // CPU threads; 0 = all cores
  float time = 0;   // animation time of this frame
  // An animation renders its frames in order with the same Method, resources
  // and targets, `time` = frameTimes[frame]. A still: one frame.
  std::vector<float> frameTimes;
  int frame = 0;
  // The loop may filter this frame over time where the method does (Method::temporal): the frames of
  // an animation, and the viewer's. frame 0 has no history.
  bool temporal = false;
  // The index of this frame's first sample: 0, or f·spp for frame f of an animation the method
  // filters over time with TemporalSettings::continueSamples.
  int firstSample = 0;
  bool progress = true;           // draw a progress bar on a terminal
  std::vector<std::string> aovs;  // extra outputs asked for (a subset of Method::outputs())
  Accumulation accumulation = Accumulation::Compensated;
  // Sample counts (< spp) at which `onCheckpoint` receives the image so far
  // (convergence plots); the last sample count is the result itself.
  std::vector<int> checkpoints;
  std::function<void(const struct RenderResult& sofar, Profiler& profiler)> onCheckpoint;
  // > 0: stop after the sample that brings the frame's wall time (set-up
  // included, GL work finished) to this many seconds (equal-time
  // comparisons); `spp` is then the most samples. At least one sample runs.
  double timeLimitS = 0;
  bool wants(const std::string& aov) const {
    for (auto& a : aovs)
      if (a == aov) return true;
    return false;
  }
};

struct RenderResult {
  Image image;
  int sppCompleted = 0;  // < requested when interrupted (Ctrl-C) or time-limited
  bool interrupted = false;
  bool timeLimited = false;                         // stopped by RenderRequest::timeLimitS
  nlohmann::json extra = nlohmann::json::object();  // method-specific stats
  std::map<std::string, Image> aovs;                // the extra outputs asked for
  std::vector<std::string> built;                   // the resources this render built (SceneResources::built)
  // The timed passes that ran once per sample (the sample loop records them);
  // the others are set-up (voxelization, light maps, uploads).
  std::vector<std::string> samplePasses;
};

// A method is what the sample loop (illum/framework/sample_loop.h) calls: it declares
// its needs, prepares each frame, and renders one sample at a time into the
// frame's sample targets; the framework owns the resources, the targets, the
// accumulation, progress, Ctrl-C, timing and the stats.
class Method {
 public:
  virtual ~Method() = default;
  // What a render reads, from the method's parameters: exactly this is built.
  virtual SceneNeeds needs() const = 0;
  // Extra output channels (AOVs) it can write besides the combined image.
  virtual std::vector<std::string> outputs() const { return {}; }
  // Once per frame, after the scene resources are current: programs,
  // per-frame constants.
  virtual void prepareFrame(Frame&) {}
  // Writes sample k (0-based; the frame's first is RenderRequest::firstSample) of the frame into the frame's sample targets
  // ("image" and each output asked for): GL methods into Frame::sampleImage
  // after the loop rendered the G-buffer, CPU methods into
  // Frame::samplePixels. Returns false if it stopped early (Ctrl-C): that
  // sample is not accumulated.
  virtual bool addSample(Frame& frame, int k) = 0;
  // After the image is read back: the method's stats into Frame::extra.
  virtual void finishFrame(Frame&) {}
  // Whether the frames of an animation are filtered over time (GL methods with a G-buffer).
  virtual TemporalSettings temporal() const { return {}; }
};

// The exact computation of the integral an approximate method estimates
// (`vgi compare` renders both): a method, its parameters, and the extra
// outputs both write (compared too). `set` is the model-matched counterpart: the exact
// integrator with exactly the method's omissions (a bounce limit, a radius, the environment,
// glossy bounces: reference's maxdepth, radius, env, glossy); `full` the full reference of the
// same quantity (the whole scene's light, every bounce, every lobe), with the same channel
// bookkeeping (env_channel), so that an error splits into the model's (model-matched against
// full) and the approximation's (the method against the model-matched).
struct Counterpart {
  std::string method;
  std::vector<std::string> set;  // key=value
  std::vector<std::string> aovs;
  // What both sides leave out or count differently from the counterpart's defaults (e.g. "neither
  // side integrates the environment light"): printed by --help-module and compare, kept in results.
  std::string note = {};
  std::vector<std::string> full = {};  // key=value for `method`: the full reference
};

// The full reference of a method whose image stands for the scene's light: `reference` path
// tracing at its defaults (every bounce to maxdepth 8, the environment, every lobe), the
// environment seen from the first surface counted as `envChannel` ("direct" or "indirect") as
// the model-matched counterpart counts it.
std::vector<std::string> fullPathReference(const std::string& envChannel = "direct");

struct MethodInfo {
  std::string name;
  std::string description;
  bool needsGl;
  std::function<std::unique_ptr<Method>(ParamSet& params, const Scene& scene)> create;
  // From the method's resolved parameters; empty for a method that is exact itself.
  std::function<Counterpart(const nlohmann::json& params)> counterpart = {};
  // An exact method on the CPU: its twin on the GL device, computing the same
  // integrals with the same parameters (reference → reference_gl), so that a
  // GL method's speed is measured against its counterpart on the same device.
  std::string glTwin = {};
};

// The registry (illum/methods/registry.cpp): each method's row is defined in its own file.
const std::vector<MethodInfo>& methodRegistry();
// Throws naming `option` and listing the known names.
const MethodInfo& findMethod(const std::string& name, const std::string& option = "--method");
std::string defaultMethodName();
// A float parameter as text that parses back to the same float (a counterpart's `set`).
std::string counterpartText(const nlohmann::json& value);  // a number or a bool as --set text

}  // namespace vgi
