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

Comparison compareWithCounterpart(const RenderOptions& opt, int refSpp, const DiffOptions& diff,
                                  const std::string& referenceFile, ExactDevice device) {
  if (refSpp < 1 || refSpp > 1 << 20) fail("--ref-spp ", refSpp, ": must be in [1, 1048576]");
  const MethodInfo& info = findMethod(opt.method);
  if (!info.counterpart)
    fail("--method ", opt.method,
         ": it has no exact counterpart (it computes its integral exactly, or it is a debug view); compare "
         "an approximate method");
  Comparison c;
  c.refSpp = refSpp;
  // The counterpart gets the method's resolved parameters (defaults that
  // depend on the scene included, e.g. the radius).
  c.choice = counterpartOnDevice(opt, info.counterpart(resolveParameters(opt)), device);
  c.counterpart = c.choice.counterpart;
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
  c.refSpp = refSpp;
  c.complete = c.approx.result.sppCompleted > 0 && c.exact.result.sppCompleted > 0;
  if (!c.complete) return c;
  c.interrupted = c.approx.result.interrupted || c.exact.result.interrupted;

  c.errors["image"] = compareImages(c.approx.result.image, c.exact.result.image, opt.method, "exact", diff);
  for (auto& a : c.counterpart.aovs)
    c.errors[a] = compareImages(c.approx.result.aovs.at(a), c.exact.result.aovs.at(a), opt.method + "." + a,
                                "exact." + a, diff);
  c.frames = std::max(1, c.approx.result.sppCompleted);
  const std::vector<std::string>& sample = c.approx.result.samplePasses;
  const nlohmann::json timings = c.approx.stats["timings_ms"];  // items() must not outlive its object
  for (auto& [pass, ms] : timings.items()) {
    const bool each = sample.empty() || std::find(sample.begin(), sample.end(), pass) != sample.end();
    (each ? c.msPerFrame : c.setupMs) += ms.get<double>();
  }
  c.msPerFrame /= c.frames;
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
  if (exact.stats.contains("reference_file")) s["exact"]["file"] = exact.stats["reference_file"];
  s["time"] = {{"method_total_ms", approx.stats["total_ms"]},
               {"method_ms_per_frame", msPerFrame},
               {"method_setup_ms", setupMs},
               {"method_wall_ms", approx.stats["wall_ms"]},
               {"method_timings_ms", approx.stats["timings_ms"]},
               {"exact_total_ms", exact.stats.value("total_ms", nlohmann::json())},
               {"exact_wall_ms", exact.stats.value("wall_ms", nlohmann::json())}};
  s["interrupted"] = interrupted;
  return s;
}

std::vector<std::string> writeComparison(const Comparison& c, const std::string& stem) {
  const std::string method = c.approx.stats["method"].get<std::string>();
  std::vector<std::string> files = writeRenderOutputs(c.approx, stem + "." + method + ".exr", 1.0f);
  for (auto& f : writeRenderOutputs(c.exact, stem + ".exact.exr", 1.0f)) files.push_back(f);
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
