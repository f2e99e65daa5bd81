#include "illum/render_job.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "core/build_info.h"
#include "core/error.h"
#include "core/image.h"
#include "core/scene_loader.h"
#include "core/shader_library.h"

namespace fs = std::filesystem;

namespace vgi {

void parseSize(const std::string& text, int& w, int& h) {
  auto x = text.find('x');
  char* end = nullptr;
  long a = -1, b = -1;
  if (x != std::string::npos) {
    a = std::strtol(text.substr(0, x).c_str(), &end, 10);
    if (*end) a = -1;
    b = std::strtol(text.substr(x + 1).c_str(), &end, 10);
    if (*end) b = -1;
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
  checkOutputFolder(path, "-o");
}

void checkOutputFolder(const std::string& path, const std::string& option) {
  fs::path dir = fs::path(path).parent_path();
  if (!dir.empty() && !fs::is_directory(dir))
    fail(option, " '", path, "': folder '", dir.string(), "' does not exist");
}

RenderOutput runRender(const RenderOptions& opt) {
  if (opt.spp < 1 || opt.spp > 1 << 20) fail("--spp ", opt.spp, ": must be in [1, 1048576]");
  if (opt.width < 1 || opt.height < 1 || opt.width > 16384 || opt.height > 16384)
    fail("--size ", opt.width, "x", opt.height, ": each side must be in [1, 16384]");
  if (opt.threads < 0 || opt.threads > 1024) fail("--threads ", opt.threads, ": must be in [0, 1024]");
  const MethodInfo& info = findMethod(opt.method);
  Scene scene = loadScene(opt.scene);

  ParamSet params;
  if (!opt.preset.empty()) {
    auto it = scene.presets.find(opt.preset);
    if (it == scene.presets.end()) {
      std::string known;
      for (auto& [k, v] : scene.presets) known += (known.empty() ? "" : ", ") + k;
      fail("--preset '", opt.preset, "': scene '", opt.scene, "' has no such preset (",
           known.empty() ? "it has none" : "known: " + known, ")");
    }
    for (auto& [k, v] : it->second) params.set(k, v, "preset '" + opt.preset + "'");
  }
  for (auto& kv : opt.set) params.setFromString(kv, "--set");
  std::unique_ptr<Method> method = info.create(params, scene);
  params.checkAllUsed("method '" + opt.method + "'");
  const std::vector<std::string> outputs = method->outputs();
  for (auto& a : opt.aovs)
    if (std::find(outputs.begin(), outputs.end(), a) == outputs.end()) {
      std::string known;
      for (auto& o : outputs) known += (known.empty() ? "" : ", ") + o;
      fail("--aov '", a, "': method '", opt.method, "' has no such output (",
           known.empty() ? "it has none besides the image" : "known: " + known, ")");
    }

  std::unique_ptr<GlContext> gl;
  std::unique_ptr<ShaderLibrary> shaders;
  if (info.needsGl) {
    gl = GlContext::create(opt.gl);
    shaders = std::make_unique<ShaderLibrary>();
  }
  RenderRequest req;
  req.scene = &scene;
  req.width = opt.width;
  req.height = opt.height;
  req.spp = opt.spp;
  req.seed = opt.seed;
  req.threads = opt.threads;
  req.time = opt.time;
  req.gl = gl.get();
  req.shaders = shaders.get();
  req.progress = opt.progress;
  req.aovs = opt.aovs;

  RenderOutput out;
  auto t0 = std::chrono::steady_clock::now();
  {
    Profiler profiler(gl != nullptr);
    out.result = method->render(req, profiler);
    profiler.resolve(true);
    nlohmann::json& s = out.stats;
    s["method"] = opt.method;
    s["scene"] = opt.scene;
    s["width"] = opt.width;
    s["height"] = opt.height;
    s["spp"] = opt.spp;
    s["spp_completed"] = out.result.sppCompleted;
    s["interrupted"] = out.result.interrupted;
    s["seed"] = opt.seed;
    s["time"] = opt.time;
    s["gl_renderer"] = gl ? gl->renderer() : "none (CPU method)";
    s["gl_version"] = gl ? gl->version() : "";
    s["gl_backend"] = gl ? gl->backendName() : "";
    s["gl_errors"] = gl ? gl->errorCount() : 0;
    s["cpu_threads_available"] = std::thread::hardware_concurrency();
    s["timings_ms"] = profiler.timingsMs();
    s["cpu_timings_ms"] = profiler.cpuTimingsMs();
    s["pass_calls"] = profiler.callCounts();
    s["total_ms"] = profiler.totalMs();
    s["params"] = params.resolved();
    s["preset"] = opt.preset;
    s["git_revision"] = gitRevision();
    s["triangles"] = scene.triangleCount();
    s["degenerate_triangles_dropped"] = scene.report.degenerateTrianglesDropped;
    s["warnings"] = scene.report.warnings;
    s["extra"] = out.result.extra;
    s["built"] = out.result.built;
    s["needs"] = info.needs;
    s["aovs"] = opt.aovs;
  }
  out.stats["wall_ms"] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (gl && gl->errorCount() > 0)
    fail("method '", opt.method, "' raised ", gl->errorCount(), " GL error(s) on ", gl->renderer(),
         "; the image is not trustworthy and was not written");
  return out;
}

std::vector<std::string> writeRenderOutputs(const RenderOutput& out, const std::string& path, float exposure) {
  checkOutputPath(path);
  fs::path stem = fs::path(path).replace_extension("");
  std::vector<std::string> files = {stem.string() + ".exr", stem.string() + ".png", stem.string() + ".json"};
  writeImage(out.result.image, files[0]);
  writeImage(out.result.image, files[1], exposure);
  for (auto& [name, image] : out.result.aovs) {
    for (const char* ext : {".exr", ".png"}) {
      files.push_back(stem.string() + "." + name + ext);
      writeImage(image, files.back(), ext[1] == 'p' ? exposure : 1.0f);
    }
  }
  nlohmann::json s = out.stats;
  s["outputs"] = files;
  s["exposure_png"] = exposure;
  std::ofstream js(files[2]);
  js << s.dump(2) << "\n";
  if (!js) fail("cannot write '", files[2], "'");
  return files;
}

std::string describeMethod(const std::string& name) {
  const MethodInfo& info = findMethod(name);
  Scene scene = loadScene("builtin:cornell");  // defaults that depend on the scene use the Cornell box
  ParamSet params;
  std::unique_ptr<Method> method = info.create(params, scene);
  std::ostringstream os;
  os << name << ": " << info.description << (info.needsGl ? " [GL]" : " [CPU]") << "\n";
  auto list = [](const std::vector<std::string>& v) {
    std::string s;
    for (auto& x : v) s += (s.empty() ? "" : ", ") + x;
    return s.empty() ? std::string("-") : s;
  };
  os << "needs: " << list(info.needs) << "\n";
  os << "outputs: image" << (method->outputs().empty() ? "" : ", " + list(method->outputs())) << " (--aov NAME,...)\n";
  os << "parameters (--set key=value; scene-dependent defaults shown for builtin:cornell):\n";
  for (auto& d : params.docs())
    os << "  " << d.key << " (" << d.type << ", default " << d.defaultValue << "): " << d.doc << "\n";
  return os.str();
}

}  // namespace vgi
