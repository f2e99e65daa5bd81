// `vgi sweep`, the experiment file read and checked (experiments/sweep.h: the format): its own
// fields, the reference, then each method expanded (sweep_expand.cpp), before anything renders.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>

#include "core/error.h"
#include "core/image.h"
#include "core/json_text.h"
#include "core/output_files.h"
#include "core/params.h"
#include "experiments/sweep_detail.h"
#include "illum/framework/render_options.h"

namespace vgi {

namespace fs = std::filesystem;

namespace sweep_detail {

std::string paramText(const nlohmann::json& v, const std::string& key) {
  std::string text;
  if (!paramTextOf(v, text)) fail("experiment: '", key, "' = ", v.dump(), " is not a number, string or bool");
  return text;
}

void checkKeys(const nlohmann::json& obj, const std::string& where, const std::set<std::string>& known) {
  if (!obj.is_object()) fail("experiment: ", where, " must be a JSON object, not ", obj.dump());
  for (auto& [k, v] : obj.items())
    if (!known.count(k)) {
      std::string list;
      for (auto& n : known) list += (list.empty() ? "" : ", ") + n;
      fail("experiment: unknown key '", k, "' in ", where, " (known: ", list, ")");
    }
}

int intIn(const nlohmann::json& v, const std::string& key, int lo, int hi) {
  if (!v.is_number_integer() || v.get<long long>() < lo || v.get<long long>() > hi)
    fail("experiment: '", key, "' = ", v.dump(), " must be an integer in [", lo, ", ", hi, "]");
  return v.get<int>();
}

std::string stringAt(const nlohmann::json& obj, const std::string& key, const std::string& where,
                     const std::string& def) {
  if (!obj.is_object() || !obj.contains(key)) return def;
  const nlohmann::json& v = obj[key];
  if (!v.is_string()) fail("experiment: '", where, "' = ", v.dump(), " must be a string");
  return v.get<std::string>();
}

double positive(const nlohmann::json& v, const std::string& key, bool zeroAllowed) {
  if (!v.is_number() || !(v.get<double>() > 0 || (zeroAllowed && v.get<double>() == 0)) ||
      !std::isfinite(v.get<double>()))
    fail("experiment: '", key, "' = ", v.dump(), " must be a ", zeroAllowed ? "non-negative" : "positive",
         " number");
  return v.get<double>();
}

}  // namespace sweep_detail

namespace {
using namespace sweep_detail;

// "frames", "time_step", "time" of the experiment or of one scene (`where` names it) over `a`.
void readAnimation(const nlohmann::json& j, const std::string& where, Experiment::Animation& a) {
  if (j.contains("frames")) a.frames = intIn(j["frames"], where + "frames", 1, 10000);
  // Renders take these as 32-bit floats: a value finite only as a double (1e300) is refused here,
  // by its key, not by every render's "--time-step inf" later.
  auto asFloat = [&](double v, const char* key) {
    if (!(std::abs(v) <= double(std::numeric_limits<float>::max())))
      fail("experiment: ", where, "'", key, "' = ", j[key].dump(), " is beyond a 32-bit float");
    return float(v);
  };
  if (j.contains("time_step"))
    a.timeStep = asFloat(positive(j["time_step"], where + "time_step"), "time_step");
  if (j.contains("time")) {
    if (!j["time"].is_number() || !std::isfinite(j["time"].get<double>()))
      fail("experiment: ", where, "'time' = ", j["time"].dump(), " must be a finite number");
    a.time = asFloat(j["time"].get<double>(), "time");
  }
}

// Every frame's time (time + k·time_step in float, as the render computes it) must be finite.
void checkAnimation(const Experiment::Animation& a, const std::string& scene) {
  const float last = a.time + float(a.frames - 1) * a.timeStep;
  if (!std::isfinite(last))
    fail("experiment: scene '", scene, "': 'time' ", a.time, " + ('frames' ", a.frames,
         " - 1) x 'time_step' ", a.timeStep, " = ",
         double(a.time) + double(a.frames - 1) * double(a.timeStep),
         ", the last frame's time, is beyond a 32-bit float");
}

// The experiment's own fields: name, scenes, size, spp, seed, checkpoints, aovs, ε, time budget.
void readExperimentHead(const nlohmann::json& j, const std::string& path, Experiment& e) {
  checkKeys(
      j, "the experiment",
      {"name", "scenes", "size", "spp", "checkpoints", "seed", "seeds", "aovs", "epsilon", "relative_epsilon",
       "dark_tolerance", "flip", "time_budget_s", "frames", "time_step", "time", "reference", "methods"});
  e.name = stringAt(j, "name", "name", fs::path(path).stem().string());
  for (const char* k : {"scenes", "size", "spp", "methods"})
    if (!j.contains(k)) fail("experiment file '", path, "': '", k, "' is missing");
  if (!j["scenes"].is_array() || j["scenes"].empty())
    fail("experiment: 'scenes' = ", j["scenes"].dump(), " must be a non-empty list of scenes");
  Experiment::Animation fallback;
  readAnimation(j, "", fallback);
  for (auto& s : j["scenes"]) {
    Experiment::Animation a = fallback;
    std::string scene;
    if (s.is_object()) {
      checkKeys(s, "a scene", {"scene", "frames", "time_step", "time"});
      scene = stringAt(s, "scene", "scenes[].scene");
      if (scene.empty()) fail("experiment: scene ", s.dump(), " needs \"scene\": a scene");
      readAnimation(s, "scene '" + scene + "' ", a);
    } else if (s.is_string()) {
      scene = s.get<std::string>();
    } else {
      fail("experiment: scene ", s.dump(), " is neither a scene nor {\"scene\": …, \"frames\": …}");
    }
    checkAnimation(a, scene);
    if (e.animation.count(scene)) fail("experiment: scene '", scene, "' is listed twice");
    e.scenes.push_back(scene);
    e.animation[scene] = a;
  }
  if (!j["size"].is_string()) fail("experiment: 'size' = ", j["size"].dump(), " must be \"WxH\"");
  parseSize(j["size"].get<std::string>(), e.width, e.height);
  e.spp = intIn(j["spp"], "spp", 1, 1 << 20);
  if (j.contains("seed")) e.seed = uint32_t(intIn(j["seed"], "seed", 0, 1 << 30));
  if (j.contains("seeds")) e.seeds = intIn(j["seeds"], "seeds", 1, 1000);
  if (j.contains("checkpoints")) {
    if (!j["checkpoints"].is_array()) fail("experiment: 'checkpoints' must be a list of sample counts");
    std::set<int> c;
    for (auto& v : j["checkpoints"]) {
      const int k = intIn(v, "checkpoints", 1, e.spp);
      if (k < e.spp) c.insert(k);
    }
    e.checkpoints.assign(c.begin(), c.end());
  }
  if (j.contains("aovs")) {
    if (!j["aovs"].is_array()) fail("experiment: 'aovs' must be a list of output names");
    for (auto& a : j["aovs"]) {
      if (!a.is_string()) fail("experiment: aov ", a.dump(), " is not a string");
      e.aovs.push_back(a.get<std::string>());
    }
  }
  if (j.contains("epsilon")) e.diff.epsilon = positive(j["epsilon"], "epsilon");
  if (j.contains("relative_epsilon")) e.relativeEpsilon = positive(j["relative_epsilon"], "relative_epsilon");
  if (j.contains("dark_tolerance"))
    e.diff.darkTolerance = positive(j["dark_tolerance"], "dark_tolerance", true);
  if (j.contains("flip")) {
    const std::string f = stringAt(j, "flip", "flip", "auto");
    if (f != "auto" && f != "ldr" && f != "hdr" && f != "off")
      fail("experiment: 'flip' = ", j["flip"].dump(), " must be \"auto\", \"ldr\", \"hdr\" or \"off\"");
    e.diff.flip = f == "off"   ? FlipMode::Off
                  : f == "ldr" ? FlipMode::Ldr
                  : f == "hdr" ? FlipMode::Hdr
                               : FlipMode::Auto;
  }
  if (j.contains("time_budget_s")) e.timeBudgetS = positive(j["time_budget_s"], "time_budget_s");
  if (e.animated()) {  // an animation's row is per frame of its whole run
    for (const char* k : {"checkpoints", "time_budget_s"})
      if (j.contains(k))
        fail("experiment: '", k,
             "' and an animation ('frames' > 1) do not go together (an animation's renders are compared "
             "whole, frame by frame)");
    if (j.contains("reference") && j["reference"].is_object() &&
        (j["reference"].contains("convergence") || j["reference"].contains("file")))
      fail(
          "experiment: an animation ('frames' > 1) does not go with 'reference.convergence' or "
          "'reference.file' (the reference is an animation)");
  }
}

// The output folder must be writable before anything renders.
void checkOutputFolder(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  const std::string probe = dir + "/.vgi_sweep_probe";
  if (ec || !std::ofstream(probe)) fail("sweep output folder '", dir, "' cannot be written");
  fs::remove(probe, ec);
}

// The experiment's "reference": its spp (returned), the convergence counts, the device, or an image file.
int readReference(const nlohmann::json& ref, const std::string& path, Experiment& e) {
  checkKeys(ref, "'reference'", {"spp", "method", "set", "file", "convergence", "device", "split"});
  if (ref.contains("split")) {
    if (!ref["split"].is_boolean())
      fail("experiment: 'reference.split' = ", jsonExcerpt(ref["split"]), " must be true or false");
    e.split = ref["split"].get<bool>();
    if (e.split && (ref.contains("file") || ref.contains("method")))
      fail(
          "experiment: 'reference.split' splits an error against the registry's model-matched counterpart "
          "and full reference; it does not go with a reference 'file' or 'method'");
  }
  if (ref.contains("device")) {
    const std::string d = stringAt(ref, "device", "reference.device");
    if (d != "same" && d != "cpu")
      fail("experiment: 'reference.device' = ", ref["device"].dump(), " must be \"same\" or \"cpu\"");
    e.exactDevice = d == "same" ? ExactDevice::Same : ExactDevice::Cpu;
    e.exactDeviceGiven = true;
  }
  if (ref.contains("file") && (ref.contains("method") || ref.contains("spp") || ref.contains("convergence")))
    fail("experiment: 'reference' has a 'file' and a method, spp or convergence: give one of them");
  const int refSpp = ref.contains("spp") ? intIn(ref["spp"], "reference.spp", 1, 1 << 20) : 256;
  if (ref.contains("convergence")) {
    if (!ref["convergence"].is_array() || ref["convergence"].empty())
      fail("experiment: 'reference.convergence' = ", ref["convergence"].dump(),
           " must be a non-empty list of sample counts");
    std::set<int> c;
    for (auto& v : ref["convergence"]) c.insert(intIn(v, "reference.convergence", 1, refSpp));
    e.curveCounts.assign(c.begin(), c.end());
  }
  if (ref.contains("file")) {
    if (e.scenes.size() != 1)
      fail("experiment: a reference 'file' stands for one scene, but 'scenes' lists ", e.scenes.size());
    SweepRender r;
    r.file = stringAt(ref, "file", "reference.file");
    if (fs::path(r.file).is_relative()) r.file = (fs::path(path).parent_path() / r.file).string();
    const Image img = readImage(r.file);  // throws naming a missing or unreadable file
    if (img.width != e.width || img.height != e.height)
      fail("experiment: reference file '", r.file, "' is ", img.width, "x", img.height,
           ", the experiment's size is ", e.width, "x", e.height);
    r.id = "file";
    r.stem = r.file;
    e.references.push_back(r);
  }

  return refSpp;
}

Experiment loadExperimentFile(const std::string& path, const std::string& dir) {
  const nlohmann::json j = readJsonFile(path, "experiment file");
  Experiment e;
  e.path = path;
  e.dir = dir;
  readExperimentHead(j, path, e);
  checkOutputFolder(dir);
  const nlohmann::json ref = j.value("reference", nlohmann::json::object());
  const int refSpp = readReference(ref, path, e);
  if (!j["methods"].is_array() || j["methods"].empty())
    fail("experiment: 'methods' must be a non-empty list of {\"method\": …}");
  ExpandState st;
  for (size_t mi = 0; mi < j["methods"].size(); ++mi) expandMethod(j, mi, ref, refSpp, e, st);
  const std::set<std::string>& written = st.written;
  // An output no method writes would be a column of blanks: refused before anything renders.
  for (const std::string& a : e.aovs)
    if (!written.count(a)) {
      std::string list;
      for (auto& w : written) list += (list.empty() ? "" : ", ") + w;
      fail("experiment: 'aovs' names '", a, "', which no method of the experiment writes (",
           list.empty() ? std::string("they write none") : "they write: " + list, ")");
    }
  return e;
}
}  // namespace

Experiment loadExperiment(const std::string& path, const std::string& dir) {
  try {
    return loadExperimentFile(path, dir);
  } catch (const Error& ex) {
    // Every message names the file: "experiment: X" becomes "experiment file 'PATH': X".
    const std::string m = ex.what(), prefix = "experiment: ";
    if (m.rfind(prefix, 0) == 0) fail("experiment file '", path, "': ", m.substr(prefix.size()));
    throw;
  }
}

bool Experiment::animated() const {
  for (auto& [scene, a] : animation)
    if (a.frames > 1) return true;
  return false;
}

}  // namespace vgi
