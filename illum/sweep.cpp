#include "illum/sweep.h"

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
#include <set>
#include <sstream>
#include <thread>

#include "core/error.h"
#include "core/image.h"
#include "illum/method.h"
#include "illum/render_job.h"

namespace vgi {

namespace fs = std::filesystem;

namespace {

// A JSON scalar as `--set` text (64 → "64", 0.5 → "0.5", true → "true").
std::string paramText(const nlohmann::json& v, const std::string& key) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  if (v.is_number()) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", v.get<double>());
    return buf;
  }
  fail("experiment: '", key, "' = ", v.dump(), " is not a number, string or bool");
}

std::string hashId(const std::vector<std::string>& parts) {
  uint64_t h = 1469598103934665603ull;  // FNV-1a 64
  for (auto& p : parts) {
    for (unsigned char c : p) h = (h ^ c) * 1099511628211ull;
    h = (h ^ 0xffu) * 1099511628211ull;
  }
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

double positive(const nlohmann::json& v, const std::string& key) {
  if (!v.is_number() || !(v.get<double>() > 0) || !std::isfinite(v.get<double>()))
    fail("experiment: '", key, "' = ", v.dump(), " must be a positive number");
  return v.get<double>();
}

std::string stemOfRender(const SweepRender& r) { return fs::path(r.stem).replace_extension("").string(); }

// Render arguments shared by points and references.
std::vector<std::string> renderArgs(const Experiment& e, const std::string& scene, const std::string& method,
                                    const std::vector<std::string>& set, int spp,
                                    const std::vector<std::string>& aovs, bool checkpoints) {
  std::vector<std::string> a = {"render", "--scene", scene, "--method", method};
  for (auto& s : set) a.insert(a.end(), {"--set", s});
  a.insert(a.end(), {"--size", std::to_string(e.width) + "x" + std::to_string(e.height), "--spp",
                     std::to_string(spp), "--seed", std::to_string(e.seed), "--quiet"});
  if (checkpoints && !e.checkpoints.empty()) {
    std::string c;
    for (int k : e.checkpoints) c += (c.empty() ? "" : ",") + std::to_string(k);
    a.insert(a.end(), {"--checkpoints", c});
  }
  if (!aovs.empty()) {
    std::string c;
    for (auto& k : aovs) c += (c.empty() ? "" : ",") + k;
    a.insert(a.end(), {"--aov", c});
  }
  return a;
}

SweepRender makeRender(const std::string& dir, const std::string& kind, const std::string& name,
                       std::vector<std::string> args) {
  SweepRender r;
  r.id = name + "-" + hashId(args);
  r.dir = dir + "/" + kind + "/" + r.id;
  r.stem = r.dir + (kind == "points" ? "/render.exr" : "/ref.exr");
  args.insert(args.end(), {"-o", r.stem});
  r.args = std::move(args);
  return r;
}

std::string shellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

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

Experiment loadExperiment(const std::string& path, const std::string& dir) {
  if (!fs::is_regular_file(path))
    fail("experiment file '", path, "' does not exist or is not a regular file");
  nlohmann::json j;
  {
    std::ifstream in(path);
    try {
      j = nlohmann::json::parse(in);
    } catch (const std::exception& ex) {
      fail("experiment file '", path, "': not valid JSON (", ex.what(), ")");
    }
  }
  checkKeys(j, "the experiment",
            {"name", "scenes", "size", "spp", "checkpoints", "seed", "aovs", "epsilon", "relative_epsilon",
             "reference", "methods"});
  Experiment e;
  e.path = path;
  e.dir = dir;
  e.name = j.value("name", fs::path(path).stem().string());
  for (const char* k : {"scenes", "size", "spp", "methods"})
    if (!j.contains(k)) fail("experiment file '", path, "': '", k, "' is missing");
  if (!j["scenes"].is_array() || j["scenes"].empty())
    fail("experiment: 'scenes' = ", j["scenes"].dump(), " must be a non-empty list of scenes");
  for (auto& s : j["scenes"]) {
    if (!s.is_string()) fail("experiment: scene ", s.dump(), " is not a string");
    e.scenes.push_back(s.get<std::string>());
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

  // The output folder must be writable before anything renders.
  std::error_code ec;
  fs::create_directories(dir, ec);
  const std::string probe = dir + "/.vgi_sweep_probe";
  if (ec || !std::ofstream(probe)) fail("sweep output folder '", dir, "' cannot be written");
  fs::remove(probe, ec);

  const nlohmann::json ref = j.value("reference", nlohmann::json::object());
  checkKeys(ref, "'reference'", {"spp", "method", "set", "file"});
  if (ref.contains("file") && (ref.contains("method") || ref.contains("spp")))
    fail("experiment: 'reference' has a 'file' and a method or spp: give one of them");
  const int refSpp = ref.contains("spp") ? intIn(ref["spp"], "reference.spp", 1, 1 << 20) : 256;
  if (ref.contains("file")) {
    if (e.scenes.size() != 1)
      fail("experiment: a reference 'file' stands for one scene, but 'scenes' lists ", e.scenes.size());
    SweepRender r;
    r.file = ref["file"].get<std::string>();
    if (fs::path(r.file).is_relative()) r.file = (fs::path(path).parent_path() / r.file).string();
    const Image img = readImage(r.file);  // throws naming a missing or unreadable file
    if (img.width != e.width || img.height != e.height)
      fail("experiment: reference file '", r.file, "' is ", img.width, "x", img.height,
           ", the experiment's size is ", e.width, "x", e.height);
    r.id = "file";
    r.stem = r.file;
    e.references.push_back(r);
  }

  if (!j["methods"].is_array() || j["methods"].empty())
    fail("experiment: 'methods' must be a non-empty list of {\"method\": …}");
  for (size_t mi = 0; mi < j["methods"].size(); ++mi) {
    const nlohmann::json& m = j["methods"][mi];
    const std::string where = "methods[" + std::to_string(mi) + "]";
    checkKeys(m, where, {"method", "label", "set", "grid"});
    if (!m.contains("method") || !m["method"].is_string())
      fail("experiment: ", where, " has no \"method\" name");
    const std::string method = m["method"].get<std::string>();
    const MethodInfo& info = findMethod(method, "experiment " + where + ".method");
    std::vector<std::string> fixed;
    const nlohmann::json set = m.value("set", nlohmann::json::object()),
                         grid = m.value("grid", nlohmann::json::object());
    for (const auto* o : {&set, &grid})
      if (!o->is_object())
        fail("experiment: ", where, o == &set ? ".set" : ".grid", " must be an object of parameters, not ",
             o->dump());
    for (auto& [k, v] : set.items()) fixed.push_back(k + "=" + paramText(v, where + ".set." + k));
    // The grid: every combination, keys in the file's (sorted) order.
    std::vector<std::pair<std::string, std::vector<std::string>>> axes;
    for (auto& [k, v] : grid.items()) {
      if (!v.is_array() || v.empty())
        fail("experiment: ", where, ".grid.", k, " = ", v.dump(), " must be a non-empty list of values");
      std::vector<std::string> values;
      for (auto& x : v) values.push_back(paramText(x, where + ".grid." + k));
      axes.emplace_back(k, values);
    }
    size_t combos = 1;
    for (auto& a : axes) combos *= a.second.size();
    if (combos > 10000) fail("experiment: ", where, " expands to ", combos, " points (at most 10000)");
    for (const std::string& scene : e.scenes)
      for (size_t c = 0; c < combos; ++c) {
        SweepPoint pt;
        pt.scene = scene;
        pt.method = method;
        pt.label = m.value("label", method);
        std::vector<std::string> set = fixed;
        size_t rest = c;
        pt.params = nlohmann::json::object();
        for (auto& [k, values] : axes) {
          const std::string& v = values[rest % values.size()];
          rest /= values.size();
          set.push_back(k + "=" + v);
          pt.params[k] = v;
        }
        RenderOptions o;
        o.scene = scene;
        o.method = method;
        o.methodGiven = true;
        o.set = set;
        o.width = e.width;
        o.height = e.height;
        o.spp = e.spp;
        nlohmann::json resolved;
        std::vector<std::string> outputs;
        try {
          resolved =
              resolveParameters(o, &outputs);  // unknown or out-of-range parameters, a scene that fails
        } catch (const Error& ex) {
          fail("experiment: ", where, " (", method, " on ", scene, ", ", pt.params.dump(), "): ", ex.what());
        }
        // Only the outputs this method writes are asked of it.
        std::vector<std::string> aovs;
        for (auto& a : e.aovs)
          if (std::find(outputs.begin(), outputs.end(), a) != outputs.end()) aovs.push_back(a);
        pt.render = makeRender(dir, "points", method, renderArgs(e, scene, method, set, e.spp, aovs, true));
        // The reference.
        SweepRender r;
        if (ref.contains("file")) {
          pt.reference = 0;
        } else {
          std::string rmethod;
          std::vector<std::string> rset, raovs;
          if (ref.contains("method")) {
            rmethod = ref["method"].get<std::string>();
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
          r = makeRender(dir, "references", rmethod,
                         renderArgs(e, scene, rmethod, rset, refSpp, raovs, false));
          auto same = std::find_if(e.references.begin(), e.references.end(),
                                   [&](const SweepRender& x) { return x.id == r.id; });
          if (same == e.references.end()) {
            RenderOptions ro;
            ro.scene = scene;
            ro.method = rmethod;
            ro.methodGiven = true;
            ro.set = rset;
            try {
              resolveParameters(ro);
            } catch (const Error& ex) {
              fail("experiment: reference of ", where, " (", rmethod, " on ", scene, "): ", ex.what());
            }
            e.references.push_back(r);
            pt.reference = e.references.size() - 1;
          } else {
            pt.reference = size_t(same - e.references.begin());
          }
        }
        e.points.push_back(std::move(pt));
      }
  }
  return e;
}

std::string sweepCommand(const SweepRender& r, const std::string& vgi) {
  std::string c = shellQuote(vgi);
  for (auto& a : r.args) c += " " + shellQuote(a);
  return c;
}

bool sweepRenderDone(const SweepRender& r, int spp) {
  if (!r.file.empty()) return true;
  const nlohmann::json s = readJson(stemOfRender(r) + ".json");
  return s.is_object() && s.value("spp_completed", 0) >= spp;
}

int runSweep(const Experiment& e, const std::string& vgi) {
  std::vector<std::pair<const SweepRender*, int>> todo;
  for (auto& r : e.references) {
    // A reference's spp is in its arguments.
    const auto it = std::find(r.args.begin(), r.args.end(), "--spp");
    const int spp = it != r.args.end() ? std::atoi((it + 1)->c_str()) : 1;
    if (!sweepRenderDone(r, spp)) todo.emplace_back(&r, spp);
  }
  for (auto& p : e.points)
    if (!sweepRenderDone(p.render, e.spp)) todo.emplace_back(&p.render, e.spp);
  int n = 0;
  std::vector<std::string> failed;
  for (auto& [r, spp] : todo) {
    fs::create_directories(r->dir);
    const std::string cmd = sweepCommand(*r, vgi);
    std::ofstream(r->dir + "/command.txt") << cmd << "\n";
    std::fprintf(stderr, "sweep %s: [%d/%zu] %s\n", e.name.c_str(), ++n, todo.size(), r->id.c_str());
    const int rc = std::system((cmd + " > " + shellQuote(r->dir + "/log.txt") + " 2>&1").c_str());
    if ((WIFSIGNALED(rc) && (WTERMSIG(rc) == SIGINT || WTERMSIG(rc) == SIGTERM)) ||
        (WIFEXITED(rc) && WEXITSTATUS(rc) == 130))
      fail("sweep: interrupted during ", r->id, " (", n - 1, " of ", todo.size(),
           " renders done); run it again to resume");
    if (rc != 0 || !sweepRenderDone(*r, spp)) failed.push_back(r->id + " (see " + r->dir + "/log.txt)");
  }
  if (!failed.empty()) {
    std::string list;
    for (auto& f : failed) list += "\n  " + f;
    fail("sweep: ", failed.size(), " of ", todo.size(), " renders failed:", list);
  }
  return n;
}

nlohmann::json collectSweep(const Experiment& e) {
  nlohmann::json rows = nlohmann::json::array();
  const std::string machine = machineName();
  DiffOptions relative;
  relative.relativeEpsilon = e.relativeEpsilon;
  std::vector<int> counts = e.checkpoints;
  counts.push_back(e.spp);
  for (const SweepPoint& p : e.points) {
    const SweepRender& ref = e.references[p.reference];
    const std::string refStem = stemOfRender(ref);
    if (ref.file.empty() && !readJson(refStem + ".json").is_object()) continue;  // not rendered yet
    for (int spp : counts) {
      std::string stem = stemOfRender(p.render);
      if (spp < e.spp) {
        char number[24];
        std::snprintf(number, sizeof number, ".spp%05d", spp);
        stem += number;
      }
      const nlohmann::json stats = readJson(stem + ".json");
      if (!stats.is_object() || !fs::exists(stem + ".exr")) continue;
      nlohmann::json row;
      row["scene"] = p.scene;
      row["method"] = p.method;
      row["label"] = p.label;
      row["params"] = p.params;
      row["resolved_params"] = stats.value("params", nlohmann::json::object());
      row["point"] = p.render.id;
      row["reference"] = ref.id;
      row["spp"] = spp;
      double sampleMs = 0, total = stats.value("total_ms", 0.0);
      const nlohmann::json timings = stats.value("timings_ms", nlohmann::json::object());
      const nlohmann::json passes = stats.value("sample_passes", nlohmann::json::array());
      for (auto& pass : passes) sampleMs += timings.value(pass.get<std::string>(), 0.0);
      if (!stats.contains("sample_passes")) sampleMs = total;  // CPU methods: all per sample
      row["time_ms"] = total;
      row["sample_ms"] = sampleMs;
      row["setup_ms"] = std::max(0.0, total - sampleMs);
      row["gl_renderer"] = stats.value("gl_renderer", "");
      row["git_revision"] = stats.value("git_revision", "");
      row["machine"] = machine;
      std::vector<std::string> channels = {"image"};
      channels.insert(channels.end(), e.aovs.begin(), e.aovs.end());
      for (auto& ch : channels) {
        const std::string a = ch == "image" ? stem + ".exr" : stem + "." + ch + ".exr";
        const std::string b = ch == "image" ? refStem + ".exr" : refStem + "." + ch + ".exr";
        if (!fs::exists(a) || !fs::exists(b)) continue;
        const Image ia = readImage(a), ib = readImage(b);
        const ImageDiff d = compareImages(ia, ib, a, b, e.diff), dr = compareImages(ia, ib, a, b, relative);
        row[ch] = {{"relmse", d.relMse},
                   {"relmse_relative", dr.relMse},
                   {"rel_mae", d.relMae},
                   {"ssim", d.ssim},
                   {"energy", (d.energyRgb[0] + d.energyRgb[1] + d.energyRgb[2]) / 3.0}};
      }
      rows.push_back(row);
    }
  }
  return rows;
}

nlohmann::json writeSweepResults(const Experiment& e) {
  const nlohmann::json rows = collectSweep(e);
  // Each finished point's signed error map against its reference (the report's third image).
  for (const SweepPoint& p : e.points) {
    const std::string a = stemOfRender(p.render) + ".exr",
                      b = stemOfRender(e.references[p.reference]) + ".exr";
    if (sweepRenderDone(p.render, e.spp) && fs::exists(b))
      writeSignedError(signedDifference(readImage(a), readImage(b)), p.render.dir + "/error.png");
  }
  nlohmann::json out = {{"experiment", e.name},
                        {"file", e.path},
                        {"size", {e.width, e.height}},
                        {"spp", e.spp},
                        {"checkpoints", e.checkpoints},
                        {"epsilon", e.diff.epsilon},
                        {"relative_epsilon", e.relativeEpsilon},
                        {"points", e.points.size()},
                        {"rows", rows}};
  std::ofstream(e.dir + "/results.json") << out.dump(2) << "\n";
  // CSV: the fixed columns, the grid's parameter keys, then per channel the metrics.
  std::set<std::string> keys;
  for (auto& p : e.points)
    for (auto& [k, v] : p.params.items()) keys.insert(k);
  std::vector<std::string> channels = {"image"};
  channels.insert(channels.end(), e.aovs.begin(), e.aovs.end());
  const std::vector<std::string> metrics = {"relmse", "relmse_relative", "rel_mae", "ssim", "energy"};
  std::ofstream csv(e.dir + "/results.csv");
  csv << "scene,method,label,point";
  for (auto& k : keys) csv << "," << k;
  csv << ",spp,time_ms,sample_ms,setup_ms";
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
        << field(r["point"]);
    for (auto& k : keys) csv << "," << field(r["params"].value(k, ""));
    csv << "," << r["spp"].get<int>() << "," << r["time_ms"].get<double>() << ","
        << r["sample_ms"].get<double>() << "," << r["setup_ms"].get<double>();
    for (auto& ch : channels)
      for (auto& m : metrics) {
        csv << ",";
        if (r.contains(ch)) csv << r[ch][m].get<double>();
      }
    csv << "," << field(r["gl_renderer"]) << "," << field(r["machine"]) << "," << field(r["git_revision"])
        << "\n";
  }
  return rows;
}

}  // namespace vgi
