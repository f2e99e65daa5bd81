#include "experiments/sweep.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "core/error.h"
#include "core/hash.h"
#include "core/image.h"
#include "core/json_text.h"
#include "core/output_files.h"
#include "core/params.h"
#include "core/warnings.h"
#include "experiments/compare.h"
#include "illum/framework/method.h"
#include "illum/framework/render_job.h"

namespace vgi {

namespace fs = std::filesystem;

namespace {

// A JSON scalar as `--set` text; anything else is refused naming the key.
std::string paramText(const nlohmann::json& v, const std::string& key) {
  std::string text;
  if (!paramTextOf(v, text)) fail("experiment: '", key, "' = ", v.dump(), " is not a number, string or bool");
  return text;
}

std::string hashId(const std::vector<std::string>& parts) {
  uint64_t h = kFnv1aOffset;
  const unsigned char separator = 0xffu;
  for (auto& p : parts) h = fnv1a(&separator, 1, fnv1a(p, h));
  char buf[20];
  std::snprintf(buf, sizeof buf, "%012llx", (unsigned long long)(h & 0xffffffffffffull));
  return buf;
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

// The string at obj[key] (JSON path `where`), or `def` where the key is absent.
std::string stringAt(const nlohmann::json& obj, const std::string& key, const std::string& where,
                     const std::string& def = "") {
  if (!obj.is_object() || !obj.contains(key)) return def;
  const nlohmann::json& v = obj[key];
  if (!v.is_string()) fail("experiment: '", where, "' = ", v.dump(), " must be a string");
  return v.get<std::string>();
}

double positive(const nlohmann::json& v, const std::string& key, bool zeroAllowed = false) {
  if (!v.is_number() || !(v.get<double>() > 0 || (zeroAllowed && v.get<double>() == 0)) ||
      !std::isfinite(v.get<double>()))
    fail("experiment: '", key, "' = ", v.dump(), " must be a ", zeroAllowed ? "non-negative" : "positive",
         " number");
  return v.get<double>();
}

std::string stemOfRender(const SweepRender& r) { return fs::path(r.stem).replace_extension("").string(); }

// The render options of points, references and counterpart curves.
RenderOptions sweepRenderOptions(const Experiment& e, const std::string& scene, const std::string& method,
                                 const std::vector<std::string>& set, int spp,
                                 const std::vector<std::string>& aovs, const std::vector<int>& checkpoints,
                                 uint32_t seed, double timeLimitS) {
  RenderOptions o;
  o.scene = scene;
  o.method = method;
  o.methodGiven = true;
  o.set = set;
  o.width = e.width;
  o.height = e.height;
  o.spp = spp;
  o.seed = seed;
  o.progress = false;
  o.aovs = aovs;
  o.checkpoints = checkpoints;
  o.timeLimitS = timeLimitS;
  const Experiment::Animation& a = e.animation.at(scene);
  o.frames = a.frames;
  o.timeStep = a.timeStep;
  o.time = a.time;
  return o;
}

SweepRender makeRender(const std::string& dir, const std::string& kind, const std::string& name,
                       const RenderOptions& options) {
  SweepRender r;
  std::vector<std::string> args = {"render"};
  for (std::string& a : renderArgs(options)) args.push_back(std::move(a));
  r.id = name + "-" + hashId(args);
  r.dir = dir + "/" + kind + "/" + r.id;
  r.stem = r.dir + (kind == "references" ? "/ref.exr" : "/render.exr");
  args.insert(args.end(), {"-o", r.stem});
  r.args = std::move(args);
  r.options = options;
  return r;
}

// The method a render runs.
std::string renderMethod(const SweepRender& r) { return r.args.empty() ? r.id : r.options.method; }

std::string machineName() {
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  return std::string(host) + " (" + std::to_string(std::thread::hardware_concurrency()) + " threads)";
}

nlohmann::json readJson(const std::string& path) {
  std::ifstream in(path);
  if (!in) return nullptr;
  try {
    return nlohmann::json::parse(in);
  } catch (const std::exception&) {
    return nullptr;  // a render killed while writing it
  }
}

}  // namespace

namespace {
Experiment loadExperimentFile(const std::string& path, const std::string& dir);
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

namespace {
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
  checkKeys(j, "the experiment",
            {"name", "scenes", "size", "spp", "checkpoints", "seed", "aovs", "epsilon", "relative_epsilon",
             "dark_tolerance", "time_budget_s", "frames", "time_step", "time", "reference", "methods"});
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
  checkKeys(ref, "'reference'", {"spp", "method", "set", "file", "convergence", "device"});
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

// The grid's axes: every key's values as text, keys in the file's (sorted) order; `combos` their
// product, refused beyond 10000.
using GridAxes = std::vector<std::pair<std::string, std::vector<std::string>>>;
GridAxes readGrid(const nlohmann::json& grid, const std::string& where, size_t& combos) {
  GridAxes axes;
  for (auto& [k, v] : grid.items()) {
    if (!v.is_array() || v.empty())
      fail("experiment: ", where, ".grid.", k, " = ", v.dump(), " must be a non-empty list of values");
    std::vector<std::string> values;
    for (auto& x : v) values.push_back(paramText(x, where + ".grid." + k));
    axes.emplace_back(k, values);
  }
  combos = 1;
  for (auto& a : axes) {
    // Checked before multiplying: 16 keys of 16 values would wrap a size_t to 0.
    if (combos > 10000 / a.second.size())
      fail("experiment: ", where, ".grid expands to more than 10000 points (", axes.size(),
           " keys; at most 10000 combinations)");
    combos *= a.second.size();
  }
  return axes;
}

// Where a point's reference comes from: the method's own "reference" (a method and its set, or
// another method's counterpart), the experiment's "reference.method", or the method's registry
// counterpart (the default).
struct ReferenceChoice {
  std::string method;
  std::vector<std::string> set, aovs;
};
ReferenceChoice chooseReference(const Experiment& e, const nlohmann::json& ref, const nlohmann::json& mref,
                                const std::string& where, const MethodInfo& info, const RenderOptions& o,
                                const nlohmann::json& resolved) {
  const std::string& method = o.method;
  ReferenceChoice rc;
  std::string& rmethod = rc.method;
  std::vector<std::string>& rset = rc.set;
  std::vector<std::string>& raovs = rc.aovs;
  if (mref.contains("method")) {
    rmethod = stringAt(mref, "method", where + ".reference.method");
    findMethod(rmethod, "experiment " + where + ".reference.method");
    const nlohmann::json refSet = mref.value("set", nlohmann::json::object());
    if (!refSet.is_object()) fail("experiment: ", where, ".reference.set must be an object of parameters");
    for (auto& [k, v] : refSet.items()) rset.push_back(k + "=" + paramText(v, where + ".reference.set." + k));
    raovs = e.aovs;
  } else if (mref.contains("variant")) {
    // The point itself with a few parameters changed (one stage made exact: an error split).
    const nlohmann::json& variant = mref["variant"];
    if (!variant.is_object() || variant.empty())
      fail("experiment: ", where, ".reference.variant must be an object of the parameters to change");
    rmethod = method;
    for (const std::string& kv : o.set)
      if (!variant.contains(kv.substr(0, kv.find('=')))) rset.push_back(kv);
    for (auto& [k, v] : variant.items())
      rset.push_back(k + "=" + paramText(v, where + ".reference.variant." + k));
    raovs = e.aovs;
  } else if (mref.contains("counterpart_of")) {
    const std::string other = stringAt(mref, "counterpart_of", where + ".reference.counterpart_of");
    const MethodInfo& oi = findMethod(other, "experiment " + where + ".reference.counterpart_of");
    if (!oi.counterpart)
      fail("experiment: ", where, ".reference.counterpart_of: '", other, "' has no counterpart");
    RenderOptions oo = o;
    oo.method = other;
    oo.set.clear();
    const Counterpart cp = oi.counterpart(resolveParameters(oo));
    rmethod = cp.method;
    rset = cp.set;
    for (auto& a : e.aovs)
      if (std::find(cp.aovs.begin(), cp.aovs.end(), a) != cp.aovs.end()) raovs.push_back(a);
  } else if (ref.contains("method")) {
    rmethod = stringAt(ref, "method", "reference.method");
    findMethod(rmethod, "experiment reference.method");
    const nlohmann::json refSet = ref.value("set", nlohmann::json::object());
    if (!refSet.is_object()) fail("experiment: reference.set must be an object of parameters");
    for (auto& [k, v] : refSet.items()) rset.push_back(k + "=" + paramText(v, "reference.set." + k));
    raovs = e.aovs;
  } else {
    if (!info.counterpart)
      fail("experiment: ", where, ": method '", method,
           "' has no exact counterpart; give "
           "\"reference\": {\"method\": …}");
    const Counterpart cp = info.counterpart(resolved);
    rmethod = cp.method;
    rset = cp.set;
    for (auto& a : e.aovs)
      if (std::find(cp.aovs.begin(), cp.aovs.end(), a) != cp.aovs.end()) raovs.push_back(a);
  }
  return rc;
}

// Registers the reference render of point `pt` (one per distinct render) and its convergence curve:
// the same integral with the next seed, against the reference, on the point's device (reference's GL
// twin for a GL method, unless reference.device is "cpu"), what each point's equal-error time is read
// off. The reference image may come from either device (the same integral). `curveMethods` caches
// the device choice per method and reference.
void addReference(Experiment& e, SweepPoint& pt, const RenderOptions& o, const ReferenceChoice& rc,
                  int refSpp, const std::string& where,
                  std::map<std::string, CounterpartChoice>& curveMethods) {
  const std::string &scene = o.scene, &method = o.method, &dir = e.dir;
  const std::string& rmethod = rc.method;
  const std::vector<std::string>&rset = rc.set, &raovs = rc.aovs;
  SweepRender r;
  r = makeRender(dir, "references", rmethod,
                 sweepRenderOptions(e, scene, rmethod, rset, refSpp, raovs, {}, e.seed, 0));
  auto same = std::find_if(e.references.begin(), e.references.end(),
                           [&](const SweepRender& x) { return x.id == r.id; });
  if (same == e.references.end()) {
    try {
      resolveParameters(r.options);
    } catch (const Error& ex) {
      fail("experiment: reference of ", where, " (", rmethod, " on ", scene, "): ", ex.what());
    }
    e.references.push_back(r);
    pt.reference = e.references.size() - 1;
  } else {
    pt.reference = size_t(same - e.references.begin());
  }
  // Its own convergence: the same integral with the next seed, against the reference,
  // on the point's device (reference's GL twin for a GL method, unless reference.device
  // is "cpu"): what each point's equal-error time is read off. The reference image may
  // come from either device (the same integral).
  if (!e.curveCounts.empty()) {
    const std::string key = method + "\n" + r.id;
    auto known = curveMethods.find(key);
    if (known == curveMethods.end()) {
      CounterpartChoice choice;
      try {
        choice = counterpartOnDevice(o, Counterpart{rmethod, rset, raovs}, e.exactDevice);
      } catch (const Error& ex) {
        fail("experiment: 'reference.device' = \"cpu\": the curve of ", where, " (", rmethod, " on ", scene,
             "): ", ex.what());
      }
      // "same", written in the file, is a demand: a curve that must leave the method's device is refused.
      if (e.exactDeviceGiven && e.exactDevice == ExactDevice::Same && !choice.sameDevice)
        fail("experiment: 'reference.device' = \"same\", but the curve of ", where, " (", method,
             ", counterpart ", rmethod, ") cannot run on the method's device: ", choice.note,
             " (say \"cpu\", or leave 'device' out to accept either)");
      known = curveMethods.emplace(key, choice).first;
    }
    const std::string& cmethod = known->second.counterpart.method;
    const std::vector<int> below(e.curveCounts.begin(), e.curveCounts.end() - 1);
    const SweepRender curve = makeRender(
        dir, "curves", cmethod,
        sweepRenderOptions(e, scene, cmethod, rset, e.curveCounts.back(), raovs, below, e.seed + 1, 0));
    auto c = std::find_if(e.curves.begin(), e.curves.end(),
                          [&](const SweepRender& x) { return x.id == curve.id; });
    if (c == e.curves.end()) {
      e.curves.push_back(curve);
      e.curveReference.push_back(pt.reference);
      e.curveChoice.push_back(known->second);
      c = e.curves.end() - 1;
    }
    pt.curve = int(c - e.curves.begin());
  }
}

// What expanding the methods gathers across them.
struct ExpandState {
  std::map<std::string, CounterpartChoice> curveMethods;  // method, reference → its curve's method, device
  std::set<std::string> written;                          // the outputs the methods write
};

// Entry `mi` of "methods": its points (scenes × grid combinations), each with its reference and curve.
void expandMethod(const nlohmann::json& j, size_t mi, const nlohmann::json& ref, int refSpp, Experiment& e,
                  ExpandState& st) {
  const std::string& dir = e.dir;
  std::map<std::string, CounterpartChoice>& curveMethods = st.curveMethods;
  std::set<std::string>& written = st.written;
  const nlohmann::json& m = j["methods"][mi];
  const std::string where = "methods[" + std::to_string(mi) + "]";
  checkKeys(m, where, {"method", "label", "set", "grid", "spp", "seed", "reference"});
  if (!m.contains("method") || !m["method"].is_string())
    fail("experiment: ", where, " has no \"method\" name");
  const std::string method = m["method"].get<std::string>();
  const MethodInfo& info = findMethod(method, "experiment " + where + ".method");
  const int spp = m.contains("spp") ? intIn(m["spp"], where + ".spp", 1, 1 << 20) : e.spp;
  const uint32_t seed = m.contains("seed") ? uint32_t(intIn(m["seed"], where + ".seed", 0, 1 << 30)) : e.seed;
  std::vector<int> checkpoints;
  for (int k : e.checkpoints)
    if (k < spp) checkpoints.push_back(k);
  // Its own reference: another method's counterpart (shared with that method's points), or a method.
  const nlohmann::json mref = m.value("reference", nlohmann::json::object());
  checkKeys(mref, where + ".reference", {"counterpart_of", "method", "set", "variant"});
  if (m.contains("reference") &&
      int(mref.contains("counterpart_of")) + int(mref.contains("method")) + int(mref.contains("variant")) !=
          1)
    fail("experiment: ", where, ".reference = ", jsonExcerpt(mref),
         " needs one of \"counterpart_of\", \"method\" or \"variant\"");
  if (mref.contains("set") && !mref.contains("method"))
    fail("experiment: ", where, ".reference.set goes with \"method\" (a variant's changes are its value)");
  std::vector<std::string> fixed;
  const nlohmann::json set = m.value("set", nlohmann::json::object()),
                       grid = m.value("grid", nlohmann::json::object());
  for (const auto* o : {&set, &grid})
    if (!o->is_object())
      fail("experiment: ", where, o == &set ? ".set" : ".grid", " must be an object of parameters, not ",
           o->dump());
  for (auto& [k, v] : set.items()) fixed.push_back(k + "=" + paramText(v, where + ".set." + k));
  size_t combos = 1;
  const GridAxes axes = readGrid(grid, where, combos);
  for (const std::string& scene : e.scenes)
    for (size_t c = 0; c < combos; ++c) {
      SweepPoint pt;
      pt.scene = scene;
      pt.method = method;
      pt.label = stringAt(m, "label", where + ".label", method);
      std::vector<std::string> set = fixed;
      size_t rest = c;
      pt.params = nlohmann::json::object();
      for (auto& [k, values] : axes) {
        const std::string& v = values[rest % values.size()];
        rest /= values.size();
        set.push_back(k + "=" + v);
        pt.params[k] = v;
      }
      RenderOptions o = sweepRenderOptions(e, scene, method, set, spp, {}, checkpoints, seed, e.timeBudgetS);
      nlohmann::json resolved;
      std::vector<std::string> outputs;
      try {
        resolved = resolveParameters(o, &outputs);  // unknown or out-of-range parameters, a scene that fails
      } catch (const Error& ex) {
        fail("experiment: ", where, " (", method, " on ", scene, ", ", pt.params.dump(), "): ", ex.what());
      }
      written.insert(outputs.begin(), outputs.end());
      // Only the outputs this method writes are asked of it.
      std::vector<std::string> aovs;
      for (auto& a : e.aovs)
        if (std::find(outputs.begin(), outputs.end(), a) != outputs.end()) aovs.push_back(a);
      o.aovs = aovs;
      pt.render = makeRender(dir, "points", method, o);
      pt.spp = spp;
      // The reference.
      if (ref.contains("file") && !m.contains("reference")) {
        pt.reference = 0;
      } else {
        addReference(e, pt, o, chooseReference(e, ref, mref, where, info, o, resolved), refSpp, where,
                     curveMethods);
      }
      e.points.push_back(std::move(pt));
    }
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

std::string sweepCommand(const SweepRender& r, const std::string& vgi) {
  std::string c = shellQuote(vgi);
  for (auto& a : r.args) c += " " + shellQuote(a);
  return c;
}

bool sweepRenderDone(const SweepRender& r, int spp) {
  if (!r.file.empty()) return true;
  const nlohmann::json s = readJson(stemOfRender(r) + ".json");
  if (!s.is_object()) return false;
  if (r.options.frames > 1) {  // every frame with every sample
    const nlohmann::json frames = s.value("frames", nlohmann::json::array());
    return !s.value("interrupted", true) && int(frames.size()) == r.options.frames && frames.is_array() &&
           frames.back().value("spp_completed", 0) >= spp;
  }
  return s.value("spp_completed", 0) >= spp || s.value("time_limited", false);
}

bool Experiment::animated() const {
  for (auto& [scene, a] : animation)
    if (a.frames > 1) return true;
  return false;
}

std::string sweepFrameStem(const SweepRender& r, int frame) {
  return r.options.frames > 1 ? frameStem(stemOfRender(r), frame) : stemOfRender(r);
}

int sweepRenderSpp(const SweepRender& r) { return r.args.empty() ? 1 : r.options.spp; }

int runSweep(const Experiment& e, const std::string& vgi) {
  std::vector<std::pair<const SweepRender*, int>> todo;
  for (const auto* list : {&e.references, &e.curves})
    for (auto& r : *list)
      if (!r.args.empty() && !sweepRenderDone(r, sweepRenderSpp(r))) todo.emplace_back(&r, sweepRenderSpp(r));
  for (auto& p : e.points)
    if (!sweepRenderDone(p.render, p.spp)) todo.emplace_back(&p.render, p.spp);
  int n = 0;
  std::vector<std::string> failed;
  for (auto& [r, spp] : todo) {
    fs::create_directories(r->dir);
    const std::string cmd = sweepCommand(*r, vgi);
    writeTextFile(cmd + "\n", r->dir + "/command.txt");
    std::fprintf(stderr, "sweep %s: [%d/%zu] %s\n", e.name.c_str(), ++n, todo.size(), r->id.c_str());
    const int rc = std::system((cmd + " > " + shellQuote(r->dir + "/log.txt") + " 2>&1").c_str());
    if ((WIFSIGNALED(rc) && (WTERMSIG(rc) == SIGINT || WTERMSIG(rc) == SIGTERM)) ||
        (WIFEXITED(rc) && WEXITSTATUS(rc) == 130))
      throw SweepInterrupted("sweep: interrupted during " + r->id + " (" + std::to_string(n - 1) + " of " +
                             std::to_string(todo.size()) + " renders done); run it again to resume");
    // The render's warnings reach the person running the sweep (once each), its error the failure list.
    std::string error;
    std::ifstream log(r->dir + "/log.txt");
    for (std::string line; std::getline(log, line);) {
      if (line.rfind("vgi: warning: ", 0) == 0) printWarning(line.substr(14));
      if (line.rfind("vgi: error: ", 0) == 0) error = ": " + line.substr(5);
    }
    if (rc != 0 || !sweepRenderDone(*r, spp))
      failed.push_back(r->id + error + " (see " + r->dir + "/log.txt)");
  }
  if (!failed.empty()) {
    std::string list;
    for (auto& f : failed) list += "\n  " + f;
    fail("sweep: ", failed.size(), " of ", todo.size(), " renders failed:", list);
  }
  return n;
}

namespace {

// <stem>.sppNNNNN of a checkpoint below the render's last sample count.
std::string checkpointStem(const SweepRender& r, int spp) {
  char number[24];
  std::snprintf(number, sizeof number, ".spp%05d", spp);
  return stemOfRender(r) + number;
}

// A render's time per image (an animation's: the mean per frame): total, in the per-sample passes,
// and the set-up (the rest).
void addTimes(const nlohmann::json& stats, nlohmann::json& row) {
  auto times = [](const nlohmann::json& s, double& total, double& sample) {
    total = s.value("total_ms", 0.0);
    sample = 0;
    const nlohmann::json timings = s.value("timings_ms", nlohmann::json::object());
    for (auto& pass : s.value("sample_passes", nlohmann::json::array()))
      sample += timings.value(pass.get<std::string>(), 0.0);
    if (!s.contains("sample_passes")) sample = total;  // CPU methods: all per sample
  };
  double total = 0, sample = 0;
  const nlohmann::json frames = stats.value("frames", nlohmann::json());
  if (frames.is_array() && !frames.empty()) {
    for (auto& f : frames) {
      double t, s;
      times(f, t, s);
      total += t;
      sample += s;
    }
    total /= double(frames.size());
    sample /= double(frames.size());
  } else {
    times(stats, total, sample);
  }
  row["time_ms"] = total;
  row["sample_ms"] = sample;
  row["setup_ms"] = std::max(0.0, total - sample);
}

// One channel's metrics, frame t of `a` against frame t of `b` (one file each for a still): the
// frames' mean static metrics and, over two or more frames, the temporal ones. Empty when a file
// is missing.
nlohmann::json channelMetrics(const Experiment& e, const std::vector<std::string>& a,
                              const std::vector<std::string>& b) {
  for (size_t t = 0; t < a.size(); ++t)
    if (!fs::exists(a[t]) || !fs::exists(b[t])) return nlohmann::json();
  DiffOptions relative;
  relative.relativeEpsilon = e.relativeEpsilon;
  relative.darkTolerance = e.diff.darkTolerance;
  std::vector<Image> ia, ib;
  double sum[7] = {0, 0, 0, 0, 0, 0, 0};
  for (size_t t = 0; t < a.size(); ++t) {
    ia.push_back(readImage(a[t]));
    ib.push_back(readImage(b[t]));
    const ImageDiff d = compareImages(ia.back(), ib.back(), a[t], b[t], e.diff),
                    dr = compareImages(ia.back(), ib.back(), a[t], b[t], relative);
    const double v[7] = {
        d.relMse, dr.relMse,     d.relMae, d.ssim, (d.energyRgb[0] + d.energyRgb[1] + d.energyRgb[2]) / 3.0,
        d.leak,   d.darkFraction};
    for (int k = 0; k < 7; ++k) sum[k] += v[k] / double(a.size());
  }
  // A metric without a value (against a black reference) is "undefined" in the row, the JSON and the CSV.
  nlohmann::json m;
  const char* names[7] = {"relmse", "relmse_relative", "rel_mae", "ssim", "energy", "leak", "dark_fraction"};
  for (int k = 0; k < 7; ++k) m[names[k]] = finiteOrUndefined(sum[k]);
  if (a.size() > 1) {
    const SequenceDiff s = compareSequences(ia, ib, a.front(), b.front());
    m["temporal_error"] = finiteOrUndefined(s.temporalError);
    m["change"] = finiteOrUndefined(s.changeA);
    m["change_reference"] = finiteOrUndefined(s.changeB);
  }
  return m;
}

// The rows of one render (a point or a counterpart curve): one per checkpoint
// it reached and one for its last image, each against the reference (an
// animation: one row, its frames against the reference's).
void addRows(const Experiment& e, const SweepRender& render, const std::vector<int>& checkpoints,
             const SweepRender& ref, const nlohmann::json& base, const std::string& machine,
             nlohmann::json& rows) {
  const nlohmann::json last = readJson(stemOfRender(render) + ".json");
  const int frames = render.options.frames;
  int completed = last.is_object() ? last.value("spp_completed", 0) : 0;
  if (frames > 1) completed = sweepRenderDone(render, render.options.spp) ? render.options.spp : 0;
  std::vector<std::pair<int, std::string>> images;
  for (int k : checkpoints)
    if (completed == 0 || k < completed) images.emplace_back(k, checkpointStem(render, k));
  if (completed > 0) images.emplace_back(completed, stemOfRender(render));
  std::vector<std::string> channels = {"image"};
  channels.insert(channels.end(), e.aovs.begin(), e.aovs.end());
  for (auto& [spp, stem] : images) {
    const nlohmann::json stats = readJson(stem + ".json");
    if (!stats.is_object() || (frames == 1 && !fs::exists(stem + ".exr"))) continue;
    nlohmann::json row = base;
    row["resolved_params"] = stats.value("params", nlohmann::json::object());
    row["reference"] = ref.id;
    row["spp"] = spp;
    if (frames > 1) row["frames"] = frames;
    addTimes(stats, row);
    row["time_limited"] = stats.value("time_limited", false);
    row["gl_renderer"] = stats.value("gl_renderer", "");
    row["git_revision"] = stats.value("git_revision", "");
    row["machine"] = machine;
    for (auto& ch : channels) {
      const std::string suffix = ch == "image" ? ".exr" : "." + ch + ".exr";
      std::vector<std::string> a, b;
      for (int t = 0; t < frames; ++t) {
        a.push_back((frames > 1 ? sweepFrameStem(render, t) : stem) + suffix);
        b.push_back(sweepFrameStem(ref, t) + suffix);
      }
      const nlohmann::json m = channelMetrics(e, a, b);
      if (!m.is_null()) row[ch] = m;
    }
    rows.push_back(row);
  }
}

}  // namespace

EqualError equalErrorTime(const std::vector<CurvePoint>& curve, double error) {
  EqualError r;
  std::vector<CurvePoint> c;
  for (auto& p : curve)
    if (p.error > 0 && std::isfinite(p.error) && p.timeMs > 0) c.push_back(p);
  if (c.empty() || !(error > 0) || !std::isfinite(error)) return r;
  std::sort(c.begin(), c.end(), [](const CurvePoint& a, const CurvePoint& b) { return a.timeMs < b.timeMs; });
  // Inside the curve: log-log interpolation between the two measurements around `error`.
  for (size_t i = 0; i + 1 < c.size(); ++i) {
    const CurvePoint &a = c[i], &b = c[i + 1];
    if ((a.error - error) * (b.error - error) <= 0 && a.error != b.error) {
      const double t = std::log(error / a.error) / std::log(b.error / a.error);
      r.timeMs = a.timeMs * std::pow(b.timeMs / a.timeMs, t);
      r.valid = true;
      return r;
    }
  }
  // Outside: Monte Carlo's rate (relMSE ∝ 1 / samples) on the per-sample time from the nearest end.
  const CurvePoint& end = error < c.back().error ? c.back() : c.front();
  const double setup = std::max(0.0, end.timeMs - end.sampleMs);
  r.timeMs = setup + std::max(end.sampleMs, 1e-9) * end.error / error;
  r.valid = true;
  r.extrapolated = true;
  return r;
}

nlohmann::json collectSweep(const Experiment& e) {
  nlohmann::json rows = nlohmann::json::array();
  const std::string machine = machineName();
  std::vector<std::string> channels = {"image"};
  channels.insert(channels.end(), e.aovs.begin(), e.aovs.end());
  // The counterparts' own curves first: each point's equal-error time is read off them.
  std::vector<nlohmann::json> curveRows(e.curves.size(), nlohmann::json::array());
  for (size_t i = 0; i < e.curves.size(); ++i) {
    const SweepRender& ref = e.references[e.curveReference[i]];
    if (!readJson(stemOfRender(ref) + ".json").is_object()) continue;
    std::string scene;
    for (auto& p : e.points)
      if (p.curve == int(i)) scene = p.scene;
    const SweepRender& curve = e.curves[i];
    const std::string method = renderMethod(curve);
    std::string label = method;  // with its parameters: two counterparts of one scene differ in them
    for (const std::string& kv : curve.options.set) label += " " + kv;
    const nlohmann::json base = {{"scene", scene},
                                 {"method", method},
                                 {"label", label + " (exact, seed " + std::to_string(e.seed + 1) + ")"},
                                 {"role", "counterpart"},
                                 {"params", nlohmann::json::object()},
                                 {"point", e.curves[i].id},
                                 {"device", e.curveChoice[i].device},
                                 {"same_device", e.curveChoice[i].sameDevice},
                                 {"note", e.curveChoice[i].note}};
    const std::vector<int> below(e.curveCounts.begin(), e.curveCounts.end() - 1);
    addRows(e, e.curves[i], below, ref, base, machine, curveRows[i]);
    for (auto& r : curveRows[i]) rows.push_back(r);
  }
  for (const SweepPoint& p : e.points) {
    const SweepRender& ref = e.references[p.reference];
    if (ref.file.empty() && !readJson(stemOfRender(ref) + ".json").is_object()) continue;  // not rendered yet
    const nlohmann::json base = {{"scene", p.scene}, {"method", p.method}, {"label", p.label},
                                 {"role", "point"},  {"params", p.params}, {"point", p.render.id}};
    nlohmann::json mine = nlohmann::json::array();
    std::vector<int> checkpoints;
    for (int k : e.checkpoints)
      if (k < p.spp) checkpoints.push_back(k);
    addRows(e, p.render, checkpoints, ref, base, machine, mine);
    for (auto& row : mine) {
      // The time the exact counterpart takes to reach this row's error (relMSE, relative ε).
      for (auto& ch : channels) {
        if (!row.contains(ch) || p.curve < 0 || curveRows[size_t(p.curve)].empty()) continue;
        std::vector<CurvePoint> curve;
        // (An error with no value, "undefined" against a black reference, has no equal-error time.)
        for (auto& c : curveRows[size_t(p.curve)])
          if (c.contains(ch) && c[ch]["relmse_relative"].is_number())
            curve.push_back({c["time_ms"].get<double>(), c["sample_ms"].get<double>(),
                             c[ch]["relmse_relative"].get<double>()});
        if (!row[ch]["relmse_relative"].is_number()) continue;
        const EqualError eq = equalErrorTime(curve, row[ch]["relmse_relative"].get<double>());
        if (!eq.valid) continue;
        row[ch]["equal_error_time_ms"] = eq.timeMs;
        row[ch]["equal_error_time_ratio"] = eq.timeMs / std::max(row["time_ms"].get<double>(), 1e-9);
        row[ch]["equal_error_extrapolated"] = eq.extrapolated;
      }
      rows.push_back(row);
    }
  }
  return rows;
}

nlohmann::json writeSweepResults(const Experiment& e) {
  const nlohmann::json rows = collectSweep(e);
  // Each finished point's signed error map against its reference (the report's third image).
  // (An animation's: of each frame, error_NNNN.png, and error.png of its first.)
  for (const SweepPoint& p : e.points) {
    const int frames = e.animation.at(p.scene).frames;
    for (int t = 0; t < frames; ++t) {
      const std::string a = sweepFrameStem(p.render, t) + ".exr",
                        b = sweepFrameStem(e.references[p.reference], t) + ".exr";
      if (!sweepRenderDone(p.render, p.spp) || !fs::exists(b)) break;
      const Image d = signedDifference(readImage(a), readImage(b));
      if (t == 0) writeSignedError(d, p.render.dir + "/error.png");
      if (frames > 1) writeSignedError(d, frameStem(p.render.dir + "/error", t) + ".png");
    }
  }
  nlohmann::json animations = nlohmann::json::object();  // the animated scenes: frames, time step, start
  for (auto& [scene, a] : e.animation)
    if (a.frames > 1) animations[scene] = {{"frames", a.frames}, {"time_step", a.timeStep}, {"time", a.time}};
  nlohmann::json out = {{"experiment", e.name},
                        {"file", e.path},
                        {"size", {e.width, e.height}},
                        {"spp", e.spp},
                        {"checkpoints", e.checkpoints},
                        {"epsilon", e.diff.epsilon},
                        {"relative_epsilon", e.relativeEpsilon},
                        {"dark_tolerance", e.diff.darkTolerance},
                        {"time_budget_s", e.timeBudgetS},
                        {"animations", animations},
                        {"convergence", e.curveCounts},
                        {"exact_device", e.exactDevice == ExactDevice::Same ? "same" : "cpu"},
                        {"exact_device_given", e.exactDeviceGiven},
                        {"points", e.points.size()},
                        {"rows", rows}};
  writeJsonFile(out, e.dir + "/results.json");
  // CSV: the fixed columns, the grid's parameter keys, then per channel the metrics.
  std::set<std::string> keys;
  for (auto& p : e.points)
    for (auto& [k, v] : p.params.items()) keys.insert(k);
  std::vector<std::string> channels = {"image"};
  channels.insert(channels.end(), e.aovs.begin(), e.aovs.end());
  std::vector<std::string> metrics = {"relmse", "relmse_relative", "rel_mae", "ssim", "energy",
                                      "leak",   "dark_fraction"};
  if (!e.curveCounts.empty()) metrics.push_back("equal_error_time_ratio");
  if (e.animated()) metrics.insert(metrics.end(), {"temporal_error", "change", "change_reference"});
  std::ostringstream csv;
  csv << "scene,method,label,role,point";
  for (auto& k : keys) csv << "," << k;
  csv << ",spp,time_ms,sample_ms,setup_ms,time_limited";
  for (auto& ch : channels)
    for (auto& m : metrics) csv << "," << ch << "_" << m;
  csv << ",gl_renderer,machine,git_revision\n";
  auto field = [](const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
  };
  for (auto& r : rows) {
    csv << field(r["scene"]) << "," << field(r["method"]) << "," << field(r["label"]) << ","
        << field(r["role"]) << "," << field(r["point"]);
    for (auto& k : keys) csv << "," << field(r["params"].value(k, ""));
    csv << "," << r["spp"].get<int>() << "," << r["time_ms"].get<double>() << ","
        << r["sample_ms"].get<double>() << "," << r["setup_ms"].get<double>() << ","
        << (r["time_limited"].get<bool>() ? "true" : "false");
    for (auto& ch : channels)
      for (auto& m : metrics) {
        csv << ",";
        if (r.contains(ch) && r[ch].contains(m))
          csv << (r[ch][m].is_number() ? jsonText(r[ch][m]) : std::string(kUndefined));
      }
    csv << "," << field(r["gl_renderer"]) << "," << field(r["machine"]) << "," << field(r["git_revision"])
        << "\n";
  }
  writeTextFile(csv.str(), e.dir + "/results.csv");
  return rows;
}

}  // namespace vgi
