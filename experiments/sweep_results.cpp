// `vgi sweep`, the results: every finished render's rows against its reference (each checkpoint,
// each channel), the equal-error time read off the counterpart's curve, results.json and
// results.csv, the error maps (experiments/sweep.h).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>
#include <thread>

#include "core/image.h"
#include "core/image_metrics.h"
#include "core/json_fields.h"
#include "core/json_text.h"
#include "core/output_files.h"
#include "experiments/sweep_detail.h"
#include "illum/run/render_job.h"
#include "illum/run/render_outputs.h"

namespace vgi {

namespace fs = std::filesystem;

namespace {
using sweep_detail::kMaxSpp;
using sweep_detail::notDone;
using sweep_detail::readJson;
using sweep_detail::stemOfRender;

// The method a render runs.
std::string renderMethod(const SweepRender& r) { return r.args.empty() ? r.id : r.options.method; }

std::string machineName() {
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  return std::string(host) + " (" + std::to_string(std::thread::hardware_concurrency()) + " threads)";
}

// A render's time per image (an animation's: the mean per frame): total, in the per-sample passes,
// and the set-up (the rest). Each field is checked as it is read (a refusal names the file and key).
void addTimes(const JsonFields& stats, nlohmann::json& row) {
  auto times = [](const JsonFields& s, double& total, double& sample) {
    total = s.numberIn("total_ms", 0.0, 0.0, 1e15);
    sample = 0;
    const JsonFields timings = s.fields("timings_ms");
    const nlohmann::json& passes = s.array("sample_passes");
    for (auto& pass : passes) {
      if (!pass.is_string()) s.bad("sample_passes", "must be a list of pass names");
      sample += timings.numberIn(pass.get<std::string>(), 0.0, 0.0, 1e15);
    }
    if (!s.has("sample_passes")) sample = total;  // CPU methods: all per sample
  };
  double total = 0, sample = 0;
  const nlohmann::json& frames = stats.array("frames");
  if (!frames.empty()) {
    for (size_t i = 0; i < frames.size(); ++i) {
      double t, s;
      times(JsonFields(frames[i], stats.origin() + " frames[" + std::to_string(i) + "]"), t, s);
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
  double sum[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0}, flipLdr = 0, flipHdr = 0;
  bool hasLdr = false, hasHdr = false;
  for (size_t t = 0; t < a.size(); ++t) {
    ia.push_back(readImage(a[t]));
    ib.push_back(readImage(b[t]));
    const ImageDiff d = compareImages(ia.back(), ib.back(), a[t], b[t], e.diff),
                    dr = compareImages(ia.back(), ib.back(), a[t], b[t], relative);
    const double v[9] = {d.relMse,
                         dr.relMse,
                         d.relMae,
                         d.ssim,
                         (d.energyRgb[0] + d.energyRgb[1] + d.energyRgb[2]) / 3.0,
                         d.leak,
                         d.darkFraction,
                         d.relMseTrimmed,
                         dr.relMseTrimmed};
    for (int k = 0; k < 9; ++k) sum[k] += v[k] / double(a.size());
    hasLdr = d.hasFlipLdr;
    hasHdr = d.hasFlipHdr;
    if (hasLdr) flipLdr += d.flipLdr.pooled.mean / double(a.size());
    if (hasHdr) flipHdr += d.flipHdr.pooled.mean / double(a.size());
  }
  // A metric without a value (against a black reference) is "undefined" in the row, the JSON and the CSV.
  nlohmann::json m;
  const char* names[9] = {"relmse",        "relmse_relative", "rel_mae",
                          "ssim",          "energy",          "leak",
                          "dark_fraction", "relmse_trimmed",  "relmse_relative_trimmed"};
  for (int k = 0; k < 9; ++k) m[names[k]] = finiteOrUndefined(sum[k]);
  if (hasLdr) m["flip_ldr"] = flipLdr;  // the mean FLIP (over the frames of an animation)
  if (hasHdr) m["flip_hdr"] = flipHdr;
  if (a.size() > 1) {
    const SequenceDiff s = compareSequences(ia, ib, a.front(), b.front());
    m["temporal_error"] = finiteOrUndefined(s.temporalError);
    m["change"] = finiteOrUndefined(s.changeA);
    m["change_reference"] = finiteOrUndefined(s.changeB);
  }
  return m;
}

// The metrics the split reports beside a row's own (total_* and model_*).
const char* const kSplitMetrics[] = {"relmse", "relmse_relative", "rel_mae",
                                     "energy", "flip_ldr",        "flip_hdr"};

// The rows of one render (a point or a counterpart curve): one per checkpoint
// it reached and one for its last image, each against the reference (an
// animation: one row, its frames against the reference's). `full`: the point's full reference
// ("split"), or null: then each channel also has total_* (the render against it) and model_* (the
// reference against it).
void addRows(const Experiment& e, const SweepRender& render, const std::vector<int>& checkpoints,
             const SweepRender& ref, const nlohmann::json& base, const std::string& machine,
             nlohmann::json& rows, const SweepRender* full = nullptr) {
  const std::string lastPath = stemOfRender(render) + ".json";
  const nlohmann::json last = readJson(lastPath);
  const int frames = render.options.frames;
  int completed = 0;
  try {
    if (!last.is_null())
      completed = int(JsonFields(last, "'" + lastPath + "'").integer("spp_completed", 0, 0, kMaxSpp));
  } catch (const Error& e) {
    notDone(e);
  }
  if (frames > 1) completed = sweepRenderDone(render, render.options.spp) ? render.options.spp : 0;
  std::vector<std::pair<int, std::string>> images;
  for (int k : checkpoints)
    if (completed == 0 || k < completed) images.emplace_back(k, checkpointStem(stemOfRender(render), k));
  if (completed > 0) images.emplace_back(completed, stemOfRender(render));
  std::vector<std::string> channels = {"image"};
  channels.insert(channels.end(), e.aovs.begin(), e.aovs.end());
  auto frameFiles = [&](const SweepRender& r, const std::string& stem, const std::string& suffix) {
    std::vector<std::string> f;
    for (int t = 0; t < frames; ++t) f.push_back((frames > 1 ? sweepFrameStem(r, t) : stem) + suffix);
    return f;
  };
  std::map<std::string, nlohmann::json> model;  // per channel: the reference against the full one
  if (full)
    for (auto& ch : channels) {
      const std::string suffix = ch == "image" ? ".exr" : "." + ch + ".exr";
      model[ch] = channelMetrics(e, frameFiles(ref, stemOfRender(ref), suffix),
                                 frameFiles(*full, stemOfRender(*full), suffix));
    }
  for (auto& [spp, stem] : images) {
    const nlohmann::json stats = readJson(stem + ".json");
    if (!stats.is_object() || (frames == 1 && !fs::exists(stem + ".exr"))) continue;
    nlohmann::json row = base;
    try {  // what the row takes from the stats, each field checked
      const JsonFields st(stats, "'" + stem + ".json'");
      row["resolved_params"] = st.object("params");
      addTimes(st, row);
      row["time_limited"] = st.flag("time_limited", false);
      row["gl_renderer"] = st.text("gl_renderer", "");
      row["git_revision"] = st.text("git_revision", "");
    } catch (const Error& e) {
      notDone(e);
      continue;
    }
    row["reference"] = ref.id;
    row["spp"] = spp;
    if (frames > 1) row["frames"] = frames;
    row["machine"] = machine;
    for (auto& ch : channels) {
      const std::string suffix = ch == "image" ? ".exr" : "." + ch + ".exr";
      std::vector<std::string> a, b;
      for (int t = 0; t < frames; ++t) {
        a.push_back((frames > 1 ? sweepFrameStem(render, t) : stem) + suffix);
        b.push_back(sweepFrameStem(ref, t) + suffix);
      }
      nlohmann::json m = channelMetrics(e, a, b);
      if (m.is_null()) continue;
      if (full) {
        const nlohmann::json total = channelMetrics(e, a, frameFiles(*full, stemOfRender(*full), suffix));
        for (const char* k : kSplitMetrics) {
          if (total.is_object() && total.contains(k)) m[std::string("total_") + k] = total[k];
          if (model[ch].is_object() && model[ch].contains(k)) m[std::string("model_") + k] = model[ch][k];
        }
      }
      row[ch] = m;
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
                                 {"role", "point"},  {"params", p.params}, {"point", p.render.id},
                                 {"seed", p.seed}};
    nlohmann::json mine = nlohmann::json::array();
    std::vector<int> checkpoints;
    for (int k : e.checkpoints)
      if (k < p.spp) checkpoints.push_back(k);
    const SweepRender* full = p.full >= 0 ? &e.references[size_t(p.full)] : nullptr;
    if (full && !readJson(stemOfRender(*full) + ".json").is_object()) continue;  // not rendered yet
    addRows(e, p.render, checkpoints, ref, base, machine, mine, full);
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
      const Image ia = readImage(a), ib = readImage(b);
      const Image d = signedDifference(ia, ib);
      if (t == 0) writeSignedError(d, p.render.dir + "/error.png");
      // The FLIP map beside it (HDR-FLIP where the sweep computes it), in the papers' magma colours.
      if (t == 0 && e.diff.flip != FlipMode::Off) {
        const ImageDiff f = compareImages(ia, ib, a, b, e.diff);
        if (f.hasFlipHdr || f.hasFlipLdr)
          writeFlipMap(f.hasFlipHdr ? f.flipHdr : f.flipLdr, p.render.dir + "/flip.png");
      }
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
                        {"flip",
                         {{"mode", e.diff.flip == FlipMode::Off   ? "off"
                                   : e.diff.flip == FlipMode::Ldr ? "ldr"
                                   : e.diff.flip == FlipMode::Hdr ? "hdr"
                                                                  : "auto"},
                          {"pixels_per_degree", e.diff.viewing.pixelsPerDegree()}}},
                        {"time_budget_s", e.timeBudgetS},
                        {"seeds", e.seeds},
                        {"split", e.split},
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
  std::vector<std::string> metrics = {"relmse", "relmse_relative", "rel_mae",       "ssim", "energy",
                                      "leak",   "dark_fraction",   "relmse_trimmed"};
  if (e.diff.flip != FlipMode::Off) metrics.insert(metrics.end(), {"flip_ldr", "flip_hdr"});
  if (e.split)
    for (const char* prefix : {"total_", "model_"})
      for (const char* k : kSplitMetrics)
        if (e.diff.flip != FlipMode::Off || std::string(k).rfind("flip", 0) != 0)
          metrics.push_back(std::string(prefix) + k);
  if (!e.curveCounts.empty()) metrics.push_back("equal_error_time_ratio");
  if (e.animated()) metrics.insert(metrics.end(), {"temporal_error", "change", "change_reference"});
  std::ostringstream csv;
  csv << "scene,method,label,role,point,seed";
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
        << field(r["role"]) << "," << field(r["point"]) << ","
        << (r.contains("seed") ? std::to_string(r["seed"].get<uint32_t>()) : std::string());
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
