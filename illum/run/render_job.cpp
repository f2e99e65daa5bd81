#include "illum/run/render_job.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "core/build_info.h"
#include "core/error.h"
#include "core/gpu_memory.h"
#include "core/image.h"
#include "core/json_text.h"
#include "core/output_files.h"
#include "core/progress.h"
#include "core/scene_loader.h"
#include "core/shader_library.h"
#include "core/warnings.h"
#include "illum/framework/sample_loop.h"

namespace fs = std::filesystem;

namespace vgi {

namespace {
// The scene preset, then --set, then the method (unknown keys are errors).
std::unique_ptr<Method> createMethod(const RenderOptions& opt, const MethodInfo& info, const Scene& scene,
                                     ParamSet& params) {
  if (!opt.preset.empty()) {
    auto it = scene.presets.find(opt.preset);
    if (it == scene.presets.end()) {
      std::string known;
      for (auto& [k, v] : scene.presets) known += (known.empty() ? "" : ", ") + k;
      fail("--preset '", opt.preset, "': scene '", opt.scene, "' has no such preset (",
           known.empty() ? "it has none" : "known: " + known, ")");
    }
    for (auto& [k, v] : it->second)
      if (k != "method") params.set(k, v, "preset '" + opt.preset + "'");
  }
  for (auto& kv : opt.set) params.setFromString(kv, "--set");
  std::unique_ptr<Method> method = info.create(params, scene);
  params.checkAllUsed("method '" + info.name + "'");
  return method;
}

}  // namespace

// What one render() reports: samples, per-pass timings, the method's stats.
nlohmann::json renderStats(const RenderResult& r, const Profiler& profiler) {
  const nlohmann::json timings = profiler.timingsMs();
  return {{"spp_completed", r.sppCompleted},
          {"timings_ms", timings},
          {"cpu_timings_ms", profiler.cpuTimingsMs()},
          {"pass_calls", profiler.callCounts()},
          {"total_ms", profiler.totalMs()},
          {"extra", r.extra},
          {"built", r.built},
          {"sample_passes", r.samplePasses}};
}

namespace {

// A method that returns a non-finite pixel must never have it written as if
// it were an image (a NaN turns black in the PNG and poisons every metric).
void checkFinite(const RenderResult& r, const std::string& method) {
  auto check = [&](const Image& img, const std::string& what) {
    for (size_t i = 0; i < img.pixels.size(); ++i) {
      const glm::vec3 c = img.pixels[i];
      if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z))
        fail("method '", method, "' computed a non-finite value in its ", what, " at pixel (",
             i % size_t(img.width), ", ", i / size_t(img.width), "): (", c.x, ", ", c.y, ", ", c.z,
             "); the scene's values overflow float there. Nothing was written");
    }
  };
  check(r.image, "image");
  for (auto& [name, image] : r.aovs) check(image, "output '" + name + "'");
}

// The method a render uses: --method, or the one the preset names (a preset
// written for one method says so with the key "method").
std::string methodFor(const RenderOptions& opt, const Scene& scene) {
  if (opt.preset.empty()) return opt.method;
  auto it = scene.presets.find(opt.preset);
  if (it == scene.presets.end()) return opt.method;  // createMethod names the error
  auto m = it->second.find("method");
  if (m == it->second.end()) return opt.method;
  if (opt.methodGiven && opt.method != m->second)
    fail("--preset '", opt.preset, "' is written for method '", m->second, "', not --method '", opt.method,
         "' (drop --method, or give --method ", m->second, ")");
  return m->second;
}
}  // namespace

nlohmann::json resolveParameters(const RenderOptions& opt, std::vector<std::string>* outputs) {
  Scene scene = loadScene(opt.scene);
  ParamSet params;
  std::unique_ptr<Method> method = createMethod(opt, findMethod(methodFor(opt, scene)), scene, params);
  if (outputs) *outputs = method->outputs();
  return params.resolved();
}

void placeLight(std::vector<Light>& lights, int index, glm::vec3 position) {
  if (index < 0 || index >= int(lights.size()))
    fail("light ", index, " does not exist: the scene has ", lights.size(), " delta lights",
         lights.empty() ? "" : " (0 … " + std::to_string(lights.size() - 1) + ")");
  if (lights[size_t(index)].type == LightType::Directional)
    fail("light ", index, " is directional (it has no position)");
  lights[size_t(index)].position = position;
  lights[size_t(index)].keyframes.clear();  // placed: it stays there (its path, if any, is left)
}

namespace {
// The scene a job renders, checked: the options, the method's name, the scene file, the camera
// (--camera) and the lights (--light) moved into it.
Scene jobScene(const RenderOptions& opt) {
  checkRenderOptions(opt);
  findMethod(opt.method);  // a misspelt --method is named before the scene is loaded
  Scene scene = loadScene(opt.scene);
  printWarnings(scene.report.warnings);
  if (opt.camera) {  // the pose at every time (no path); the scene's cut-away distance stays
    const float clipNear = scene.camera.clipNear;
    scene.camera = *opt.camera;
    scene.camera.clipNear = clipNear;
    scene.cameraPath.clear();
    checkSceneRanges(scene, "--camera '" + cameraText(*opt.camera) + "'");
  }
  for (auto& [index, position] : opt.lightPositions) {
    try {
      placeLight(scene.lights, index, position);
      checkSceneRanges(scene, "the moved light");
    } catch (const Error& e) {
      fail("--light ", lightPositionText(index, position), ": ", e.what(), " in '", opt.scene, "'");
    }
  }
  return scene;
}

// Method `o.method` on `scene` with its parameters, its outputs (--aov) and its needs checked.
std::unique_ptr<Method> checkedMethod(const RenderOptions& o, const MethodInfo& info, const Scene& scene,
                                      ParamSet& params) {
  std::unique_ptr<Method> method = createMethod(o, info, scene, params);
  const std::vector<std::string> outputs = method->outputs();
  for (auto& a : o.aovs)
    if (std::find(outputs.begin(), outputs.end(), a) == outputs.end()) {
      std::string known;
      for (auto& out : outputs) known += (known.empty() ? "" : ", ") + out;
      fail("--aov '", a, "': method '", info.name, "' has no such output (",
           known.empty() ? "it has none besides the image" : "known: " + known, ")");
    }
  method->needs().check(info.name, info.needsGl);
  return method;
}
}  // namespace

void checkRenderJob(const RenderOptions& options) {
  const Scene scene = jobScene(options);
  RenderOptions o = options;
  o.method = methodFor(options, scene);
  ParamSet params;
  checkedMethod(o, findMethod(o.method), scene, params);
}

RenderJob::RenderJob(const RenderOptions& options, GlContext* gl) : opt_(options) {
  scene_ = jobScene(opt_);
  scene_.placeLightsAt(opt_.time);  // what the stats describe: the lights at the (first) time
  gl_ = gl;
  setMethod(methodFor(opt_, scene_), opt_.set, opt_.aovs);
  baselineMemory_ = measuredMemory(this->gl() != nullptr);
}

RenderJob::~RenderJob() = default;

void RenderJob::setMethod(const std::string& name, const std::vector<std::string>& set,
                          const std::vector<std::string>& aovs) {
  RenderOptions o = opt_;
  o.method = name;
  o.set = set;
  o.aovs = aovs;
  const MethodInfo& info = findMethod(o.method);
  auto params = std::make_unique<ParamSet>();
  std::unique_ptr<Method> method = checkedMethod(o, info, scene_, *params);
  if (info.needsGl && !gl_) {
    ownGl_ = GlContext::create(o.gl);
    gl_ = ownGl_.get();
  }
  if (info.needsGl && !shaders_) shaders_ = std::make_unique<ShaderLibrary>();
  const SceneNeeds needs = method->needs();
  // Everything checked: the new method replaces the old one. The resources are kept when the new
  // method needs the same (a parameter that does not change them, e.g. the ray count).
  const bool keep = resources_ && resources_->needs() == needs && info_->needsGl == info.needsGl;
  method_ = std::move(method);
  params_ = std::move(params);
  info_ = &info;
  if (!keep) makeResources(needs);
  opt_.method = name;
  opt_.set = set;
  opt_.aovs = aovs;
}

void RenderJob::lightsChanged() { resources_->lightsChanged(); }

void RenderJob::placeLightsAt(float time) {
  if (!scene_.hasLightPaths()) return;
  scene_.placeLightsAt(time);
  lightsChanged();
}

void RenderJob::makeResources(SceneNeeds needs) {
  auto fresh =
      std::make_unique<SceneResources>(scene_, std::move(needs), gl(), shaders(), frameTimes(), opt_.threads);
  if (resources_) fresh->adopt(*resources_);  // what is built the same way is kept
  resources_.reset();  // the rest of the old GL objects go before the new ones are made (at update)
  resources_ = std::move(fresh);
}

std::vector<float> RenderJob::frameTimes() const {
  std::vector<float> t;
  for (int f = 0; f < opt_.frames; ++f) t.push_back(opt_.time + float(f) * opt_.timeStep);
  return t;
}

RenderRequest RenderJob::request() const {
  RenderRequest req;
  req.scene = &scene_;
  req.method = info_->name;
  req.accumulation = opt_.accumulation;
  req.checkpoints = opt_.checkpoints;
  req.timeLimitS = opt_.timeLimitS;
  req.width = opt_.width;
  req.height = opt_.height;
  req.spp = opt_.spp;
  req.seed = opt_.seed;
  req.threads = opt_.threads;
  req.progress = opt_.progress && opt_.frames == 1;
  req.aovs = opt_.aovs;
  req.frameTimes = frameTimes();
  req.temporal = opt_.frames > 1;
  req.time = opt_.time;
  return req;
}

ShaderLibrary* RenderJob::shaders() const { return info_->needsGl ? shaders_.get() : nullptr; }
GlContext* RenderJob::gl() const { return info_->needsGl ? gl_ : nullptr; }

nlohmann::json RenderJob::describe() const {
  const SceneNeeds needs = method_->needs();
  GlContext* gl = this->gl();
  nlohmann::json run;
  run["method"] = info_->name;
  run["scene"] = opt_.scene;
  run["width"] = opt_.width;
  run["height"] = opt_.height;
  run["spp"] = opt_.spp;
  run["seed"] = opt_.seed;
  run["time"] = opt_.time;
  const Camera c = scene_.cameraAt(opt_.time);
  run["camera"] = {{"position", {c.position.x, c.position.y, c.position.z}},
                   {"target", {c.target.x, c.target.y, c.target.z}},
                   {"up", {c.up.x, c.up.y, c.up.z}},
                   {"fov_y_deg", c.fovYDeg},
                   {"near", c.clipNear},
                   {"path_keys", scene_.cameraPath.size()},
                   {"option", cameraText(c)}};
  nlohmann::json lights = nlohmann::json::array();
  for (size_t i = 0; i < scene_.lights.size(); ++i) {
    const Light& l = scene_.lights[i];
    nlohmann::json j = {{"type", lightTypeName(l.type)}};
    if (l.type != LightType::Directional) {
      j["position"] = {l.position.x, l.position.y, l.position.z};
      j["option"] = lightPositionText(int(i), l.position);  // vgi render --light
    }
    lights.push_back(j);
  }
  run["lights"] = lights;
  run["gl_renderer"] = gl ? gl->renderer() : "none (CPU method)";
  run["gl_version"] = gl ? gl->version() : "";
  run["gl_backend"] = gl ? gl->backendName() : "";
  run["cpu_threads_available"] = std::thread::hardware_concurrency();
  run["params"] = params_->resolved();
  run["preset"] = opt_.preset;
  run["git_revision"] = gitRevision();
  run["vgi_version"] = version();
  run["shader_dir"] = defaultShaderDir();
  run["triangles"] = scene_.triangleCount();
  run["degenerate_triangles_dropped"] = scene_.report.degenerateTrianglesDropped;
  run["warnings"] = scene_.report.warnings;
  run["needs"] = needs.names();
  run["accumulation"] = opt_.accumulation == Accumulation::Compensated ? "compensated" : "plain";
  run["aovs"] = opt_.aovs;
  run["memory"] = memory();
  // What renders this again: `vgi render --job THIS.json` (the method as resolved, a preset's included).
  RenderOptions job = opt_;
  job.method = info_->name;
  run["job"] = renderJobJson(job);
  return run;
}

nlohmann::json RenderJob::memory(const nlohmann::json& extra) const {
  const double method = extra.is_object() ? extra.value("state_bytes", 0.0) : 0.0;
  return memoryAgainstResources(measuredMemory(gl() != nullptr), baselineMemory_, resources_->bytes(), method,
                                targets_.bytes());
}

void RenderJob::checkGl() const {
  GlContext* gl = this->gl();
  if (gl && gl->errorCount() > 0)
    fail("method '", info_->name, "' raised ", gl->errorCount(), " GL error(s) on ", gl->renderer(),
         "; the image is not trustworthy and was not written");
}

void RenderJob::checkFiniteResult(const RenderResult& r) const { checkFinite(r, info_->name); }

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// A still: one frame, with checkpoints at the sample counts asked for.
RenderOutput renderStillJob(RenderJob& job, const RenderOptions& opt, const CheckpointSink& onCheckpoint,
                            Clock::time_point t0) {
  const std::string& name = job.info().name;
  GlContext* gl = job.gl();
  RenderRequest req = job.request();
  const nlohmann::json run = job.describe();
  req.time = opt.time;
  job.placeLightsAt(req.time);
  Profiler profiler(gl != nullptr);
  if (onCheckpoint)
    req.onCheckpoint = [&](const RenderResult& sofar, Profiler& p) {
      checkFinite(sofar, name);
      RenderOutput c;
      c.result = sofar;
      c.stats = run;
      p.resolve(true);
      c.stats.update(renderStats(sofar, p));
      c.stats["checkpoint"] = true;
      c.stats["wall_ms"] = msSince(t0);
      onCheckpoint(sofar.sppCompleted, c);
    };
  RenderOutput out;
  out.result = renderFrame(job.method(), req, job.resources(), job.targets(), job.shaders(), profiler);
  profiler.resolve(true);
  checkFinite(out.result, name);
  nlohmann::json& s = out.stats;
  s = run;
  s.update(renderStats(out.result, profiler));
  s["interrupted"] = out.result.interrupted;
  s["time_limit_s"] = opt.timeLimitS;
  s["time_limited"] = out.result.timeLimited;
  s["gl_errors"] = gl ? gl->errorCount() : 0;
  s["memory"] = job.memory(out.result.extra);  // with the resources built (describe ran before)
  s["wall_ms"] = msSince(t0);
  job.checkGl();
  return out;
}

// An animation: one Profiler per frame; the run's timings are their sums.
RenderOutput renderAnimationJob(RenderJob& job, const RenderOptions& opt, const FrameSink& onFrame,
                                Clock::time_point t0) {
  GlContext* gl = job.gl();
  RenderRequest req = job.request();
  nlohmann::json run = job.describe();
  if (!job.scene().hasDynamicMeshes() && job.scene().cameraPath.empty() && !job.scene().hasLightPaths()) {
    const std::string still = "--frames " + std::to_string(opt.frames) +
                              ": the scene has no dynamic meshes, no camera path and no light path, so every "
                              "frame shows the same instant";
    run["warnings"].push_back(still);
    printWarning(still);
  }
  nlohmann::json frames = nlohmann::json::array(), timings = nlohmann::json::object(),
                 cpuTimings = nlohmann::json::object(), calls = nlohmann::json::object();
  auto addInto = [](nlohmann::json& sum, const nlohmann::json& part) {
    for (auto& [k, v] : part.items())
      sum[k] = (sum.contains(k) ? sum[k].get<double>() : 0.0) + v.get<double>();
  };
  RenderOutput out;
  ProgressBar bar("frames", opt.frames);
  bool interrupted = false;
  for (int f = 0; f < opt.frames && !interrupted; ++f) {
    req.frame = f;
    req.time = req.frameTimes[size_t(f)];
    const TemporalSettings temporal = job.method().temporal();
    req.firstSample = temporal.on && temporal.continueSamples ? f * opt.spp : 0;
    job.placeLightsAt(req.time);
    const auto tf = Clock::now();
    Profiler profiler(gl != nullptr);
    out.result = renderFrame(job.method(), req, job.resources(), job.targets(), job.shaders(), profiler);
    profiler.resolve(true);
    job.checkGl();
    checkFinite(out.result, job.info().name);
    interrupted = out.result.interrupted || interruptRequested();
    // Stopped before every pixel of this frame had a sample: the frames so far stand, this one is not
    // written.
    if (out.result.sppCompleted == 0) break;
    nlohmann::json fs = renderStats(out.result, profiler);
    fs["frame"] = f;
    fs["time"] = req.time;
    fs["wall_ms"] = msSince(tf);
    addInto(timings, fs["timings_ms"]);
    addInto(cpuTimings, fs["cpu_timings_ms"]);
    addInto(calls, fs["pass_calls"]);
    out.stats = run;
    out.stats.update(fs);
    if (onFrame) onFrame(f, out);
    frames.push_back(fs);
    if (opt.progress) bar.advance();
  }
  bar.finish();
  nlohmann::json& s = out.stats;
  s = run;
  s["frames_requested"] = opt.frames;
  s["frames_completed"] = frames.size();
  s["time_step"] = opt.timeStep;
  s["interrupted"] = interrupted;
  s["gl_errors"] = gl ? gl->errorCount() : 0;
  s["timings_ms"] = timings;
  s["cpu_timings_ms"] = cpuTimings;
  s["pass_calls"] = calls;
  double total = 0;
  for (auto& [k, v] : timings.items()) total += v.get<double>();
  s["total_ms"] = total;
  s["built"] = out.result.built;
  s["frames"] = frames;
  s["memory"] = job.memory(out.result.extra);
  s["wall_ms"] = msSince(t0);
  return out;
}

}  // namespace

RenderOutput runRender(const RenderOptions& opt, const FrameSink& onFrame,
                       const CheckpointSink& onCheckpoint) {
  RenderJob job(opt);
  const auto t0 = Clock::now();
  return opt.frames == 1 ? renderStillJob(job, opt, onCheckpoint, t0)
                         : renderAnimationJob(job, opt, onFrame, t0);
}

}  // namespace vgi
