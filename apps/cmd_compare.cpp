// vgi compare: an approximate method against the exact computation of the same
// integral (its registry counterpart, e.g. nearfield → reference
// integrator=nearfield with the same radius and env), rendered with the same
// scene, size, seed and time: speed against error in one command.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "apps/commands.h"
#include "core/error.h"
#include "core/image_metrics.h"
#include "core/progress.h"
#include "illum/render_job.h"

namespace vgi::app {

namespace {
std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (auto& x : v) s += (s.empty() ? "" : " ") + x;
  return s;
}
}  // namespace

void addCompareCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("compare", "Render a method and its exact counterpart; report speed against error");
  auto opt = std::make_shared<RenderOptions>();
  auto args = std::make_shared<RenderArgs>();
  auto out = std::make_shared<std::string>("compare.exr");
  auto refSpp = std::make_shared<int>(256);
  auto diffOptions = std::make_shared<DiffOptions>();
  opt->method = "nearfield";
  args->size = "256x256";
  // (--spp and --set are the method's; the counterpart gets --ref-spp and the
  // parameters the registry derives from the method's.)
  addRenderOptions(cmd, *opt, *args);
  cmd->add_option("--ref-spp", *refSpp, "the exact counterpart's samples per pixel")->capture_default_str();
  addDiffOptions(cmd, *diffOptions);
  cmd->add_option("-o,--output", *out,
                  "stem.exr: writes stem.<method>.*, stem.exact.* (images, AOVs, stats) and stem.json (the comparison)")
      ->capture_default_str();
  cmd->callback([=] {
    applyRenderArgs(*args, *opt);
    opt->methodGiven = true;  // compare is about this method: a preset written for another one is an error
    if (*refSpp < 1 || *refSpp > 1 << 20) fail("--ref-spp ", *refSpp, ": must be in [1, 1048576]");
    checkOutputPath(*out);
    const MethodInfo& info = findMethod(opt->method);
    if (!info.counterpart)
      fail("--method ", opt->method, ": it computes its integral exactly; compare an approximate method with it");
    installInterruptHandler();

    // The counterpart gets the method's resolved parameters (defaults that
    // depend on the scene included, e.g. the radius).
    const Counterpart c = info.counterpart(resolveParameters(*opt));
    RenderOptions m = *opt;
    m.aovs = c.aovs;
    RenderOutput approx = runRender(m);
    RenderOptions r = *opt;
    r.method = c.method;
    r.set = c.set;
    r.preset.clear();
    r.spp = *refSpp;
    r.aovs = c.aovs;
    RenderOutput exact = interruptRequested() ? RenderOutput{} : runRender(r);
    if (approx.result.sppCompleted == 0 || exact.result.sppCompleted == 0) {
      std::fprintf(stderr, "interrupted before both renders had a full sample: nothing written\n");
      throw Interrupted{};
    }

    const std::string stem = std::filesystem::path(*out).replace_extension("").string();
    std::vector<std::string> files = writeRenderOutputs(approx, stem + "." + opt->method + ".exr", 1.0f);
    for (auto& f : writeRenderOutputs(exact, stem + ".exact.exr", 1.0f)) files.push_back(f);
    // Signed error images (method − exact) per channel: where it is too bright (red) or too dark (blue).
    auto writeError = [&](const Image& a, const Image& b, const std::string& channel) {
      const Image e = signedDifference(a, b);
      for (const char* ext : {".exr", ".png"}) {
        files.push_back(stem + ".error" + (channel == "image" ? "" : "." + channel) + ext);
        writeSignedError(e, files.back());
      }
    };
    writeError(approx.result.image, exact.result.image, "image");
    for (auto& a : c.aovs) writeError(approx.result.aovs.at(a), exact.result.aovs.at(a), a);

    nlohmann::json s;
    s["scene"] = opt->scene;
    s["method"] = opt->method;
    s["method_params"] = approx.stats["params"];
    s["exact"] = {{"method", c.method}, {"set", c.set}, {"spp", *refSpp}};
    s["size"] = {opt->width, opt->height};
    s["seed"] = opt->seed;
    s["gl_renderer"] = approx.stats["gl_renderer"];
    s["git_revision"] = approx.stats["git_revision"];
    std::map<std::string, ImageDiff> errors;
    errors["image"] = compareImages(approx.result.image, exact.result.image, opt->method, "exact", *diffOptions);
    for (auto& a : c.aovs)
      errors[a] = compareImages(approx.result.aovs.at(a), exact.result.aovs.at(a), opt->method + "." + a,
                                "exact." + a, *diffOptions);
    for (auto& [name, d] : errors) s["error"][name] = d.toJson();
    // Per frame: the passes the method runs per sample; the rest
    // (voxelization, light maps, uploads) is set-up, paid once per scene (or
    // per animation frame). A method that does not split: all per frame.
    const int frames = std::max(1, approx.result.sppCompleted);
    const std::vector<std::string>& sample = approx.result.samplePasses;
    double perFrame = 0, setup = 0;
    for (auto& [pass, ms] : approx.stats["timings_ms"].items()) {
      const bool each = sample.empty() || std::find(sample.begin(), sample.end(), pass) != sample.end();
      (each ? perFrame : setup) += ms.get<double>();
    }
    perFrame /= frames;
    s["time"] = {{"method_total_ms", approx.stats["total_ms"]},
                 {"method_ms_per_frame", perFrame},
                 {"method_setup_ms", setup},
                 {"method_wall_ms", approx.stats["wall_ms"]},
                 {"method_timings_ms", approx.stats["timings_ms"]},
                 {"exact_total_ms", exact.stats["total_ms"]},
                 {"exact_wall_ms", exact.stats["wall_ms"]}};
    s["outputs"] = files;
    s["interrupted"] = approx.result.interrupted || exact.result.interrupted;
    const std::string json = stem + ".json";
    writeJsonFile(s, json);

    std::printf("%s vs exact (%s %s, %d spp) on %s, %dx%d\n", opt->method.c_str(), c.method.c_str(),
                joined(c.set).c_str(), *refSpp, opt->scene.c_str(), opt->width, opt->height);
    std::printf("  %-10s%s\n", "channel", diffHeader());
    std::vector<std::string> channels = {"image"};
    channels.insert(channels.end(), c.aovs.begin(), c.aovs.end());
    for (auto& name : channels) std::printf("  %-10s%s\n", name.c_str(), diffLine(errors.at(name)).c_str());
    std::printf("  time: %s %.1f ms per frame + %.0f ms set-up (%d frames, timed passes; wall %.0f ms) on %s\n",
                opt->method.c_str(), perFrame, setup, frames, approx.stats["wall_ms"].get<double>(),
                approx.stats["gl_renderer"].get<std::string>().c_str());
    std::printf("        exact %.0f ms (wall %.0f ms)\n", exact.stats["total_ms"].get<double>(),
                exact.stats["wall_ms"].get<double>());
    std::fflush(stdout);
    std::fprintf(stderr, "wrote %s and %zu image/stat files\n", json.c_str(), files.size());
    if (s["interrupted"].get<bool>()) throw Interrupted{};
  });
}

}  // namespace vgi::app
