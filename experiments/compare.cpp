#include "experiments/compare.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/json_text.h"
#include "core/output_files.h"
#include "core/progress.h"
#include "illum/run/render_outputs.h"

namespace vgi {

nlohmann::json CounterpartChoice::toJson() const {
  nlohmann::json j = {{"method", counterpart.method},
                      {"set", counterpart.set},
                      {"device", device},
                      {"same_device", sameDevice}};
  if (!note.empty()) j["note"] = note;
  return j;
}

CounterpartChoice counterpartOnDevice(const RenderOptions& method, const Counterpart& registry,
                                      ExactDevice device) {
  const bool gl = findMethod(method.method).needsGl;
  CounterpartChoice c;
  c.counterpart = registry;
  auto addNote = [&](const std::string& n) { c.note += (c.note.empty() ? "" : "; ") + n; };
  if (!registry.note.empty()) addNote(registry.note);
  const MethodInfo& exact = findMethod(registry.method);
  c.device = exact.needsGl ? "gl" : "cpu";
  if (gl && !exact.needsGl && !exact.glTwin.empty() && device == ExactDevice::Same) {
    RenderOptions twin = method;
    twin.method = exact.glTwin;
    twin.set = registry.set;
    twin.preset.clear();
    try {
      resolveParameters(twin);
      c.counterpart.method = exact.glTwin;
      c.device = "gl";
    } catch (const Error& e) {
      addNote(exact.glTwin + " refuses these parameters, so the counterpart runs on the CPU: " + e.what());
    }
  } else if (gl && !exact.needsGl && device == ExactDevice::Same) {
    addNote(registry.method + " has no GL twin");
  } else if (exact.needsGl && device == ExactDevice::Cpu) {
    // Asked for the CPU: a GL counterpart (a reference naming reference_gl) becomes the CPU method
    // whose twin it is, or is refused — never run on GL while the results say "cpu".
    const MethodInfo* cpu = nullptr;
    for (const MethodInfo& m : methodRegistry())
      if (m.glTwin == exact.name) cpu = &m;
    if (!cpu) fail("the exact device is the CPU, but the counterpart ", exact.name, " runs on GL only");
    RenderOptions onCpu = method;
    onCpu.method = cpu->name;
    onCpu.set = registry.set;
    onCpu.preset.clear();
    try {
      resolveParameters(onCpu);
    } catch (const Error& e) {
      fail("the exact device is the CPU, but ", cpu->name, " (the CPU twin of ", exact.name,
           ") refuses the counterpart's parameters: ", e.what());
    }
    c.counterpart.method = cpu->name;
    c.device = "cpu";
  }
  c.sameDevice = c.device == (gl ? "gl" : "cpu");
  return c;
}

SeedStat seedStat(const std::vector<double>& values) {
  SeedStat s;
  s.values = values;
  if (values.empty()) return s;
  // One value, or a render the seed does not change: that value exactly, no rounding.
  if (std::all_of(values.begin(), values.end(), [&](double v) { return v == values[0]; })) {
    s.mean = values[0];
    return s;
  }
  for (double v : values) s.mean += v / double(values.size());
  double ss = 0;
  for (double v : values) ss += (v - s.mean) * (v - s.mean);
  s.sd = std::sqrt(ss / double(values.size() - 1));
  return s;
}

SeedStat Comparison::overSeeds(const std::string& channel, const std::string& metric, bool total) const {
  std::vector<double> v;
  for (const SeedRun& r : runs)
    v.push_back(seedMetric((total ? r.totalErrors : r.errors).at(channel), metric));
  return seedStat(v);
}

const std::vector<std::string>& seedMetricNames() {
  static const std::vector<std::string> names = {"relmse", "relmse_trimmed", "rel_mae", "energy", "flip"};
  return names;
}

double seedMetric(const ImageDiff& d, const std::string& name) {
  if (name == "relmse") return d.relMse;
  if (name == "relmse_trimmed") return d.relMseTrimmed;
  if (name == "rel_mae") return d.relMae;
  if (name == "energy") return (d.energyRgb[0] + d.energyRgb[1] + d.energyRgb[2]) / 3.0;
  return d.flipMean();
}

namespace {
// The passes of a method's render that ran per sample, per frame, and the rest (set-up).
void splitTimes(const RenderOutput& o, double& msPerFrame, double& setupMs) {
  msPerFrame = setupMs = 0;
  const int frames = std::max(1, o.result.sppCompleted);
  const std::vector<std::string>& sample = o.result.samplePasses;
  const nlohmann::json timings = o.stats["timings_ms"];  // items() must not outlive its object
  for (auto& [pass, ms] : timings.items()) {
    const bool each = sample.empty() || std::find(sample.begin(), sample.end(), pass) != sample.end();
    (each ? msPerFrame : setupMs) += ms.get<double>();
  }
  msPerFrame /= frames;
}
}  // namespace

Comparison compareWithCounterpart(const RenderOptions& opt, int refSpp, const DiffOptions& diff,
                                  const std::string& referenceFile, ExactDevice device, bool split,
                                  int seeds) {
  if (refSpp < 1 || refSpp > 1 << 20) fail("--ref-spp ", refSpp, ": must be in [1, 1048576]");
  if (seeds < 1 || seeds > 1000) fail("--seeds ", seeds, ": must be in [1, 1000]");
  const MethodInfo& info = findMethod(opt.method);
  if (!info.counterpart)
    fail("--method ", opt.method,
         ": it has no exact counterpart (it computes its integral exactly, or it is a debug view); compare "
         "an approximate method");
  Comparison c;
  c.refSpp = refSpp;
  // The counterpart gets the method's resolved parameters (defaults that
  // depend on the scene included, e.g. the radius).
  const Counterpart registry = info.counterpart(resolveParameters(opt));
  c.choice = counterpartOnDevice(opt, registry, device);
  c.counterpart = c.choice.counterpart;
  c.split = split;
  if (split) {
    if (registry.full.empty())
      fail("--method ", opt.method,
           ": its registry row names no full reference, so its error cannot be split");
    c.fullChoice =
        counterpartOnDevice(opt, Counterpart{registry.method, registry.full, registry.aovs}, device);
  }
  if (!referenceFile.empty()) {
    // The counterpart given as an image: read (and size-checked) before the method renders.
    const std::string stem = std::filesystem::path(referenceFile).replace_extension("").string();
    c.exact.result.image = readImage(referenceFile);
    const Image& ref = c.exact.result.image;
    if (ref.width != opt.width || ref.height != opt.height)
      fail("--reference '", referenceFile, "' is ", ref.width, "x", ref.height, ", the render is ", opt.width,
           "x", opt.height);
    std::vector<std::string> aovs;
    for (auto& a : c.counterpart.aovs)
      if (std::filesystem::exists(stem + "." + a + ".exr")) {
        c.exact.result.aovs[a] = readImage(stem + "." + a + ".exr");
        aovs.push_back(a);
      }
    c.counterpart.aovs = aovs;
    c.exact.result.sppCompleted = 1;
    std::ifstream statsFile(stem + ".json");
    try {
      if (statsFile) c.exact.stats = nlohmann::json::parse(statsFile);
    } catch (const std::exception&) {
      c.exact.stats = nlohmann::json::object();  // not a stats file: the image alone
    }
    if (!c.exact.stats.is_object()) c.exact.stats = nlohmann::json::object();
    // What is read from the stats is checked: a sample count and two times, as vgi writes them.
    const nlohmann::json& st = c.exact.stats;
    if (st.contains("spp") && !(st["spp"].is_number_integer() && st["spp"].get<double>() >= 1 &&
                                st["spp"].get<double>() <= double(1 << 20)))
      fail("--reference '", referenceFile, "': its stats '", stem,
           ".json' say \"spp\": ", jsonExcerpt(st["spp"]), ", not a sample count in [1, 1048576]");
    for (const char* key : {"total_ms", "wall_ms"})
      if (st.contains(key) &&
          !(st[key].is_number() && st[key].get<double>() >= 0 && std::isfinite(st[key].get<double>())))
        fail("--reference '", referenceFile, "': its stats '", stem, ".json' say \"", key,
             "\": ", jsonExcerpt(st[key]), ", not a time in milliseconds");
    refSpp = st.contains("spp") ? st["spp"].get<int>() : 0;
    c.exact.stats["reference_file"] = referenceFile;
  }
  RenderOptions m = opt;
  m.aovs = c.counterpart.aovs;
  c.approx = runRender(m);
  RenderOptions r = opt;
  r.method = c.counterpart.method;
  r.set = c.counterpart.set;
  r.preset.clear();
  r.spp = refSpp;
  r.aovs = c.counterpart.aovs;
  if (referenceFile.empty() && !interruptRequested()) c.exact = runRender(r);
  if (split && !interruptRequested()) {
    RenderOptions f = r;
    f.method = c.fullChoice.counterpart.method;
    f.set = c.fullChoice.counterpart.set;
    f.spp = c.refSpp;
    f.seed = c.fullSeed = opt.seed + kFullReferenceSeedOffset;
    c.full = runRender(f);
  }
  c.refSpp = refSpp;
  c.complete = c.approx.result.sppCompleted > 0 && c.exact.result.sppCompleted > 0 &&
               (!split || c.full.result.sppCompleted > 0);
  if (!c.complete) return c;
  c.interrupted = c.approx.result.interrupted || c.exact.result.interrupted || c.full.result.interrupted;

  std::vector<std::string> channels = {"image"};
  channels.insert(channels.end(), c.counterpart.aovs.begin(), c.counterpart.aovs.end());
  auto channel = [](const RenderOutput& o, const std::string& a) -> const Image& {
    return a == "image" ? o.result.image : o.result.aovs.at(a);
  };
  auto suffix = [](const std::string& a) { return a == "image" ? std::string() : "." + a; };
  // One seed's run of the method against the counterpart (and the full reference).
  auto addRun = [&](const RenderOutput& o, uint32_t seed) {
    SeedRun run;
    run.seed = seed;
    for (const std::string& a : channels) {
      run.errors[a] = compareImages(channel(o, a), channel(c.exact, a), opt.method + suffix(a),
                                    "exact" + suffix(a), diff);
      if (split)
        run.totalErrors[a] = compareImages(channel(o, a), channel(c.full, a), opt.method + suffix(a),
                                           "full" + suffix(a), diff);
    }
    splitTimes(o, run.msPerFrame, run.setupMs);
    c.runs.push_back(std::move(run));
  };
  addRun(c.approx, opt.seed);
  if (split)
    for (const std::string& a : channels)
      c.modelErrors[a] = compareImages(channel(c.exact, a), channel(c.full, a), "exact" + suffix(a),
                                       "full" + suffix(a), diff);
  for (int k = 1; k < seeds && !interruptRequested(); ++k) {
    RenderOptions mk = m;
    mk.seed = opt.seed + kSeedStride * uint32_t(k);
    const RenderOutput o = runRender(mk);
    if (o.result.interrupted || o.result.sppCompleted == 0) {
      c.interrupted = true;
      break;
    }
    addRun(o, mk.seed);
  }
  c.errors = c.runs[0].errors;
  c.totalErrors = c.runs[0].totalErrors;
  c.frames = std::max(1, c.approx.result.sppCompleted);
  c.msPerFrame = c.runs[0].msPerFrame;
  c.setupMs = c.runs[0].setupMs;
  return c;
}

nlohmann::json Comparison::summary() const {
  nlohmann::json s;
  s["scene"] = approx.stats["scene"];
  s["method"] = approx.stats["method"];
  s["method_params"] = approx.stats["params"];
  s["exact"] = choice.toJson();
  s["exact"]["spp"] = refSpp;
  s["size"] = {approx.stats["width"], approx.stats["height"]};
  s["seed"] = approx.stats["seed"];
  s["gl_renderer"] = approx.stats["gl_renderer"];
  s["git_revision"] = approx.stats["git_revision"];
  for (auto& [name, d] : errors) s["error"][name] = d.toJson();
  if (split) {
    s["full"] = fullChoice.toJson();
    s["full"]["spp"] = refSpp;
    s["full"]["seed"] = fullSeed;
    for (auto& [name, d] : errors)
      s["split"][name] = {{"total", totalErrors.at(name).toJson()},
                          {"model", modelErrors.at(name).toJson()},
                          {"approximation", d.toJson()}};
  }
  if (exact.stats.contains("reference_file")) s["exact"]["file"] = exact.stats["reference_file"];
  s["time"] = {{"method_total_ms", approx.stats["total_ms"]},
               {"method_ms_per_frame", msPerFrame},
               {"method_setup_ms", setupMs},
               {"method_wall_ms", approx.stats["wall_ms"]},
               {"method_timings_ms", approx.stats["timings_ms"]},
               {"exact_total_ms", exact.stats.value("total_ms", nlohmann::json())},
               {"exact_wall_ms", exact.stats.value("wall_ms", nlohmann::json())}};
  if (split) {
    s["time"]["full_total_ms"] = full.stats.value("total_ms", nlohmann::json());
    s["time"]["full_wall_ms"] = full.stats.value("wall_ms", nlohmann::json());
  }
  s["interrupted"] = interrupted;
  if (runs.size() > 1) {
    // Every metric's mean and standard deviation over the seeds, per channel (and split).
    nlohmann::json& j = s["seeds"];
    j["count"] = runs.size();
    for (auto& r : runs) j["seeds"].push_back(r.seed);
    auto stat = [&](const std::string& channel, const std::string& metric, bool total) {
      const SeedStat st = overSeeds(channel, metric, total);
      nlohmann::json values = nlohmann::json::array();
      for (double x : st.values) values.push_back(finiteOrUndefined(x));
      return nlohmann::json{
          {"mean", finiteOrUndefined(st.mean)}, {"sd", finiteOrUndefined(st.sd)}, {"values", values}};
    };
    std::vector<double> times;
    for (auto& r : runs) times.push_back(r.msPerFrame);
    const SeedStat t = seedStat(times);
    j["method_ms_per_frame"] = {{"mean", t.mean}, {"sd", t.sd}, {"values", times}};
    for (auto& [channel, d] : errors)
      for (const std::string& metric : seedMetricNames()) {
        j["error"][channel][metric] = stat(channel, metric, false);
        if (split) j["total"][channel][metric] = stat(channel, metric, true);
      }
  }
  return s;
}

std::vector<std::string> writeComparison(const Comparison& c, const std::string& stem) {
  const std::string method = c.approx.stats["method"].get<std::string>();
  std::vector<std::string> files = writeRenderOutputs(c.approx, stem + "." + method + ".exr", 1.0f);
  for (auto& f : writeRenderOutputs(c.exact, stem + ".exact.exr", 1.0f)) files.push_back(f);
  if (c.split)
    for (auto& f : writeRenderOutputs(c.full, stem + ".full.exr", 1.0f)) files.push_back(f);
  // Signed error images (method − exact) per channel: where it is too bright (red) or too dark (blue).
  auto writeError = [&](const Image& a, const Image& b, const std::string& channel) {
    const Image e = signedDifference(a, b);
    for (const char* ext : {".exr", ".png"}) {
      files.push_back(stem + ".error" + (channel == "image" ? "" : "." + channel) + ext);
      writeSignedError(e, files.back());
    }
    // The FLIP map beside it (HDR-FLIP where it was computed), in the papers' magma colours.
    const ImageDiff& d = c.errors.at(channel);
    if (d.hasFlipHdr || d.hasFlipLdr) {
      files.push_back(stem + ".flip" + (channel == "image" ? "" : "." + channel) + ".png");
      writeFlipMap(d.hasFlipHdr ? d.flipHdr : d.flipLdr, files.back());
    }
  };
  writeError(c.approx.result.image, c.exact.result.image, "image");
  for (auto& a : c.counterpart.aovs) writeError(c.approx.result.aovs.at(a), c.exact.result.aovs.at(a), a);
  nlohmann::json s = c.summary();
  s["outputs"] = files;
  files.push_back(stem + ".json");
  writeJsonFile(s, files.back());
  return files;
}

}  // namespace vgi
