// vgi compare: experiments/compare.h (a method against its exact counterpart) with
// the render options of the command line, and a printed summary.
#include <cstdio>
#include <filesystem>

#include "apps/commands.h"
#include "core/error.h"
#include "core/image_metrics.h"
#include "core/progress.h"
#include "experiments/compare.h"
#include "illum/run/render_job.h"
#include "illum/run/render_outputs.h"

namespace vgi::app {

namespace {
std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (auto& x : v) s += (s.empty() ? "" : " ") + x;
  return s;
}
}  // namespace

void addCompareCommand(CLI::App& app) {
  auto* cmd =
      app.add_subcommand("compare", "Render a method and its exact counterpart; report speed against error");
  auto opt = std::make_shared<RenderOptions>();
  auto args = std::make_shared<RenderArgs>();
  auto out = std::make_shared<std::string>("compare.exr");
  auto refSpp = std::make_shared<int>(256);
  auto reference = std::make_shared<std::string>();
  auto diffOptions = std::make_shared<DiffOptions>();
  auto exactDevice = std::make_shared<std::string>("same");
  opt->method = "nearfield";
  args->size = "256x256";
  // (--spp and --set are the method's; the counterpart gets --ref-spp and the
  // parameters the registry derives from the method's.)
  addRenderOptions(cmd, *opt, *args);
  cmd->add_option("--ref-spp", *refSpp, "the exact counterpart's samples per pixel")->capture_default_str();
  cmd->add_option("--reference", *reference,
                  "an existing image of the exact counterpart (e.g. an earlier stem.exact.exr; its AOVs and "
                  "stats beside it) instead of rendering it");
  cmd->add_option(
         "--exact-device", *exactDevice,
         "where the exact counterpart runs: same (the method's device: reference_gl for a GL method, "
         "so the times compare algorithms on one device) or cpu (reference, Embree)")
      ->check(CLI::IsMember({"same", "cpu"}))
      ->capture_default_str();
  addDiffOptions(cmd, *diffOptions);
  cmd->add_option("-o,--output", *out,
                  "stem.exr: writes stem.<method>.*, stem.exact.* (images, AOVs, stats) and stem.json (the "
                  "comparison)")
      ->capture_default_str();
  cmd->callback([=] {
    applyRenderArgs(*args, *opt);
    opt->methodGiven = true;  // compare is about this method: a preset written for another one is an error
    checkOutputPath(*out);
    installInterruptHandler();
    const Comparison c = compareWithCounterpart(*opt, *refSpp, *diffOptions, *reference,
                                                *exactDevice == "cpu" ? ExactDevice::Cpu : ExactDevice::Same);
    if (!c.complete) {
      std::fprintf(stderr, "interrupted before both renders had a full sample: nothing written\n");
      throw Interrupted{};
    }
    const std::string stem = std::filesystem::path(*out).replace_extension("").string();
    const std::vector<std::string> files = writeComparison(c, stem);
    const std::string& json = files.back();
    const RenderOutput& approx = c.approx;
    const RenderOutput& exact = c.exact;
    const double perFrame = c.msPerFrame, setup = c.setupMs;
    const int frames = c.frames;

    std::printf("%s vs exact (%s %s, %d spp, on the %s: %s device) on %s, %dx%d\n", opt->method.c_str(),
                c.counterpart.method.c_str(), joined(c.counterpart.set).c_str(), c.refSpp,
                c.choice.device == "gl" ? "GL device" : "CPU", c.choice.sameDevice ? "the same" : "another",
                opt->scene.c_str(), opt->width, opt->height);
    if (!c.choice.note.empty()) std::printf("  note: %s\n", c.choice.note.c_str());
    std::printf("  %-10s%s\n", "channel", diffHeader(diffOptions->flip != FlipMode::Off).c_str());
    std::vector<std::string> channels = {"image"};
    channels.insert(channels.end(), c.counterpart.aovs.begin(), c.counterpart.aovs.end());
    for (auto& name : channels) std::printf("  %-10s%s\n", name.c_str(), diffLine(c.errors.at(name)).c_str());
    std::printf(
        "  time: %s %.1f ms per frame + %.0f ms set-up (%d frames, timed passes; wall %.0f ms) on %s\n",
        opt->method.c_str(), perFrame, setup, frames, approx.stats["wall_ms"].get<double>(),
        approx.stats["gl_renderer"].get<std::string>().c_str());
    if (exact.stats.contains("total_ms") && exact.stats.contains("wall_ms"))
      std::printf("        exact %.0f ms (wall %.0f ms)%s\n", exact.stats["total_ms"].get<double>(),
                  exact.stats["wall_ms"].get<double>(), reference->empty() ? "" : ", when it was rendered");
    else
      std::printf("        exact: the reference image %s\n", reference->c_str());
    std::fflush(stdout);
    std::fprintf(stderr, "wrote %s and %zu image/stat files\n", json.c_str(), files.size() - 1);
    if (c.interrupted) throw Interrupted{};
  });
}

}  // namespace vgi::app
