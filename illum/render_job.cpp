#include "illum/render_job.h"

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
#include "core/image.h"
#include "core/json_text.h"
#include "core/output_files.h"
#include "core/progress.h"
#include "core/scene_loader.h"
#include "core/shader_library.h"
#include "illum/sample_loop.h"

namespace fs = std::filesystem;

namespace vgi {

void parseSize(const std::string& text, int& w, int& h) {
  auto x = text.find('x');
  // Each side parsed from a string that outlives the check of `end` (a
  // substr() temporary would be destroyed before *end is read).
  auto side = [](const std::string& digits) {
    if (digits.empty() || digits.size() > 9) return -1L;
    char* end = nullptr;
    long v = std::strtol(digits.c_str(), &end, 10);
    return *end ? -1L : v;
  };
  long a = -1, b = -1;
  if (x != std::string::npos) {
    a = side(text.substr(0, x));
    b = side(text.substr(x + 1));
  }
  if (a < 1 || b < 1 || a > 16384 || b > 16384)
    fail("--size '", text, "': expected WxH with 1 <= W, H <= 16384 (e.g. 512x512)");
  w = int(a);
  h = int(b);
}

void checkOutputPath(const std::string& path) {
  fs::path p(path);
  std::string ext = p.extension().string();
  if (ext != ".exr" && ext != ".png")
    fail("-o '", path, "': the output must end in .exr or .png (both are written, plus a .json sidecar)");
  checkOutputFile(path, "-o");
}

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

RenderOutput runRender(const RenderOptions& opt, const FrameSink& onFrame,
                       const CheckpointSink& onCheckpoint) {
  if (opt.spp < 1 || opt.spp > 1 << 20) fail("--spp ", opt.spp, ": must be in [1, 1048576]");
  if (opt.width < 1 || opt.height < 1 || opt.width > 16384 || opt.height > 16384)
    fail("--size ", opt.width, "x", opt.height, ": each side must be in [1, 16384]");
  if (opt.threads < 0 || opt.threads > 1024) fail("--threads ", opt.threads, ": must be in [0, 1024]");
  if (opt.frames < 1 || opt.frames > 100000) fail("--frames ", opt.frames, ": must be in [1, 100000]");
  if (!std::isfinite(opt.time) || !std::isfinite(opt.timeStep))
    fail("--time ", opt.time, " / --time-step ", opt.timeStep, ": must be finite numbers");
  findMethod(opt.method);  // a misspelt --method is named before the scene is loaded
  Scene scene = loadScene(opt.scene);
  const MethodInfo& info = findMethod(methodFor(opt, scene));
  ParamSet params;
  std::unique_ptr<Method> method = createMethod(opt, info, scene, params);
  const std::vector<std::string> outputs = method->outputs();
  for (auto& a : opt.aovs)
    if (std::find(outputs.begin(), outputs.end(), a) == outputs.end()) {
      std::string known;
      for (auto& o : outputs) known += (known.empty() ? "" : ", ") + o;
      fail("--aov '", a, "': method '", info.name, "' has no such output (",
           known.empty() ? "it has none besides the image" : "known: " + known, ")");
    }

  if (!opt.checkpoints.empty() && opt.frames > 1)
    fail("--checkpoints applies to a still; --frames ", opt.frames, " renders an animation");
  if (!(opt.timeLimitS >= 0) || !std::isfinite(opt.timeLimitS))
    fail("--time-limit ", opt.timeLimitS, ": must be a finite number of seconds >= 0 (0 = no limit)");
  if (opt.timeLimitS > 0 && opt.frames > 1)
    fail("--time-limit applies to a still; --frames ", opt.frames, " renders an animation");
  for (int c : opt.checkpoints)
    if (c < 1 || c > opt.spp)
      fail("--checkpoints: ", c, " is not a sample count in [1, --spp ", opt.spp, "]");

  std::unique_ptr<GlContext> gl;
  std::unique_ptr<ShaderLibrary> shaders;
  if (info.needsGl) {
    gl = GlContext::create(opt.gl);
    shaders = std::make_unique<ShaderLibrary>();
  }
  const SceneNeeds needs = method->needs();
  needs.check(info.name, info.needsGl);
  RenderRequest req;
  req.scene = &scene;
  req.method = info.name;
  req.accumulation = opt.accumulation;
  req.checkpoints = opt.checkpoints;
  req.timeLimitS = opt.timeLimitS;
  req.width = opt.width;
  req.height = opt.height;
  req.spp = opt.spp;
  req.seed = opt.seed;
  req.threads = opt.threads;
  req.progress = opt.progress && opt.frames == 1;
  req.aovs = opt.aovs;
  for (int f = 0; f < opt.frames; ++f) req.frameTimes.push_back(opt.time + float(f) * opt.timeStep);
  // The framework's, kept across the frames of an animation.
  SceneResources resources(scene, needs, gl.get(), shaders.get(), req.frameTimes, opt.threads);
  SampleTargets targets;

  // What describes the run (the same for every frame).
  nlohmann::json run;
  run["method"] = info.name;
  run["scene"] = opt.scene;
  run["width"] = opt.width;
  run["height"] = opt.height;
  run["spp"] = opt.spp;
  run["seed"] = opt.seed;
  run["time"] = opt.time;
  run["gl_renderer"] = gl ? gl->renderer() : "none (CPU method)";
  run["gl_version"] = gl ? gl->version() : "";
  run["gl_backend"] = gl ? gl->backendName() : "";
  run["cpu_threads_available"] = std::thread::hardware_concurrency();
  run["params"] = params.resolved();
  run["preset"] = opt.preset;
  run["git_revision"] = gitRevision();
  run["vgi_version"] = version();
  run["shader_dir"] = defaultShaderDir();
  run["triangles"] = scene.triangleCount();
  run["degenerate_triangles_dropped"] = scene.report.degenerateTrianglesDropped;
  run["warnings"] = scene.report.warnings;
  run["needs"] = needs.names();
  run["accumulation"] = opt.accumulation == Accumulation::Compensated ? "compensated" : "plain";
  run["aovs"] = opt.aovs;
  auto checkGl = [&] {
    if (gl && gl->errorCount() > 0)
      fail("method '", info.name, "' raised ", gl->errorCount(), " GL error(s) on ", gl->renderer(),
           "; the image is not trustworthy and was not written");
  };

  RenderOutput out;
  const auto t0 = std::chrono::steady_clock::now();
  if (opt.frames == 1) {
    req.time = opt.time;
    Profiler profiler(gl != nullptr);
    if (onCheckpoint)
      req.onCheckpoint = [&](const RenderResult& sofar, Profiler& p) {
        checkFinite(sofar, info.name);
        RenderOutput c;
        c.result = sofar;
        c.stats = run;
        p.resolve(true);
        c.stats.update(renderStats(sofar, p));
        c.stats["checkpoint"] = true;
        c.stats["wall_ms"] =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        onCheckpoint(sofar.sppCompleted, c);
      };
    out.result = renderFrame(*method, req, resources, targets, shaders.get(), profiler);
    profiler.resolve(true);
    checkFinite(out.result, info.name);
    nlohmann::json& s = out.stats;
    s = run;
    s.update(renderStats(out.result, profiler));
    s["interrupted"] = out.result.interrupted;
    s["time_limit_s"] = opt.timeLimitS;
    s["time_limited"] = out.result.timeLimited;
    s["gl_errors"] = gl ? gl->errorCount() : 0;
    out.stats["wall_ms"] =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    checkGl();
    return out;
  }

  // An animation: one Profiler per frame; the run's timings are their sums.
  if (!scene.hasDynamicMeshes())
    run["warnings"].push_back("--frames " + std::to_string(opt.frames) +
                              ": the scene has no dynamic meshes, so every frame shows the same instant");
  nlohmann::json frames = nlohmann::json::array(), timings = nlohmann::json::object(),
                 cpuTimings = nlohmann::json::object(), calls = nlohmann::json::object();
  auto addInto = [](nlohmann::json& sum, const nlohmann::json& part) {
    for (auto& [k, v] : part.items())
      sum[k] = (sum.contains(k) ? sum[k].get<double>() : 0.0) + v.get<double>();
  };
  ProgressBar bar("frames", opt.frames);
  bool interrupted = false;
  for (int f = 0; f < opt.frames && !interrupted; ++f) {
    req.frame = f;
    req.time = req.frameTimes[size_t(f)];
    const auto tf = std::chrono::steady_clock::now();
    Profiler profiler(gl != nullptr);
    out.result = renderFrame(*method, req, resources, targets, shaders.get(), profiler);
    profiler.resolve(true);
    checkGl();
    checkFinite(out.result, info.name);
    interrupted = out.result.interrupted || interruptRequested();
    // Stopped before every pixel of this frame had a sample: the frames so far stand, this one is not
    // written.
    if (out.result.sppCompleted == 0) break;
    nlohmann::json fs = renderStats(out.result, profiler);
    fs["frame"] = f;
    fs["time"] = req.time;
    fs["wall_ms"] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - tf).count();
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
  s["wall_ms"] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

namespace {

// <stem>.exr, <stem>.png, then <stem>.<aov>.exr/.png per extra output.
std::vector<std::string> writeImages(const RenderResult& r, const std::string& stem, float exposure) {
  std::vector<std::string> files = {stem + ".exr", stem + ".png"};
  writeImage(r.image, files[0]);
  writeImage(r.image, files[1], exposure);
  for (auto& [name, image] : r.aovs) {
    for (const char* ext : {".exr", ".png"}) {
      files.push_back(stem + "." + name + ext);
      writeImage(image, files.back(), ext[1] == 'p' ? exposure : 1.0f);
    }
  }
  return files;
}

void writeStats(nlohmann::json s, const std::string& json, const std::vector<std::string>& files,
                float exposure) {
  s["outputs"] = files;
  s["exposure_png"] = exposure;
  writeJsonFile(s, json);
}

std::string stemOf(const std::string& path) {
  checkOutputPath(path);
  return fs::path(path).replace_extension("").string();
}

}  // namespace

std::vector<std::string> writeRenderOutputs(const RenderOutput& out, const std::string& path,
                                            float exposure) {
  const std::string stem = stemOf(path);
  std::vector<std::string> files = writeImages(out.result, stem, exposure);
  files.insert(files.begin() + 2, stem + ".json");
  writeStats(out.stats, stem + ".json", files, exposure);
  return files;
}

std::vector<std::string> writeCheckpointOutputs(const RenderOutput& out, const std::string& path, int spp,
                                                float exposure) {
  char number[24];
  std::snprintf(number, sizeof number, ".spp%05d", spp);
  const std::string stem = stemOf(path) + number;
  std::vector<std::string> files = writeImages(out.result, stem, exposure);
  files.insert(files.begin() + 2, stem + ".json");
  writeStats(out.stats, stem + ".json", files, exposure);
  return files;
}

std::vector<std::string> writeFrameImages(const RenderOutput& out, const std::string& path, int frame,
                                          float exposure) {
  char number[16];
  std::snprintf(number, sizeof number, "_%04d", frame);
  return writeImages(out.result, stemOf(path) + number, exposure);
}

std::string writeAnimationStats(const RenderOutput& out, const std::string& path,
                                const std::vector<std::string>& files, float exposure) {
  const std::string json = stemOf(path) + ".json";
  writeStats(out.stats, json, files, exposure);
  return json;
}

std::string describeMethod(const std::string& name, const std::string& sceneSpec) {
  const MethodInfo& info = findMethod(name, "--help-module");
  Scene scene = loadScene(sceneSpec);  // defaults that depend on the scene (the radius) are this scene's
  ParamSet params;
  std::unique_ptr<Method> method = info.create(params, scene);
  std::ostringstream os;
  os << name << ": " << info.description << (info.needsGl ? " [GL]" : " [CPU]") << "\n";
  auto list = [](const std::vector<std::string>& v) {
    std::string s;
    for (auto& x : v) s += (s.empty() ? "" : ", ") + x;
    return s.empty() ? std::string("-") : s;
  };
  os << "needs: " << list(method->needs().names()) << " (with these defaults)\n";
  os << "outputs: image" << (method->outputs().empty() ? "" : ", " + list(method->outputs()))
     << " (--aov NAME,...)\n";
  os << "parameters (--set key=value; scene-dependent defaults shown for " << sceneSpec << "):\n";
  for (auto& d : params.docs())
    os << "  " << d.key << " (" << d.type << ", default " << d.defaultValue << "): " << d.doc << "\n";
  return os.str();
}

}  // namespace vgi
