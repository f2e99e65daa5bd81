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
// Each metric's mean ± standard deviation over the seeds (the model error: once, as the
// counterpart and the full reference render once).
void printSeedTable(const Comparison& c, const std::vector<std::string>& channels) {
  std::string seeds;
  for (auto& r : c.runs) seeds += (seeds.empty() ? "" : ", ") + std::to_string(r.seed);
  std::printf("  over %zu seeds (%s), mean ± standard deviation:\n", c.runs.size(), seeds.c_str());
  std::printf("  %-10s%-8s", "channel", "error");
  for (const char* h : {"relMSE", "relMSE (top 0.1 % out)", "rel. MAE", "energy", "FLIP"})
    std::printf("%-24s", h);
  std::printf("\n");
  for (const std::string& ch : channels)
    for (const char* kind : {"approx", "total", "model"}) {
      const bool total = std::string(kind) == "total", model = std::string(kind) == "model";
      if ((total || model) && !c.split) continue;
      std::printf("  %-10s%-8s", std::string(kind) == "approx" ? ch.c_str() : "", kind);
      for (const std::string& metric : seedMetricNames()) {
        char cellText[64];
        if (model) {
          std::snprintf(cellText, sizeof cellText, "%.4g (once)", seedMetric(c.modelErrors.at(ch), metric));
        } else {
          const SeedStat s = c.overSeeds(ch, metric, total);
          std::snprintf(cellText, sizeof cellText, "%.4g ± %.2g", s.mean, s.sd);
        }
        std::printf(model ? "%-24s" : "%-25s", cellText);  // (± is two bytes, one column)
      }
      std::printf("\n");
    }
  // A method that renders the same image for every seed (one without random numbers, as `direct`
  // without area lights) has a spread of 0 because nothing is random across runs, not noise-free.
  bool same = true;
  for (auto& r : c.runs) same = same && r.errors.at("image").relMse == c.runs[0].errors.at("image").relMse;
  if (same)
    std::printf(
        "  note: the method renders the same image with every seed (nothing in it is drawn from the "
        "seed): a standard deviation of 0 says nothing about its error\n");
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
  auto split = std::make_shared<bool>(true);
  auto seeds = std::make_shared<int>(1);
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
  cmd->add_flag("--split,!--no-split", *split,
                "also render the full reference (every bounce, every lobe, the environment: the registry's "
                "Counterpart::full) with --ref-spp samples and seed + 2, and split each channel's error "
                "into total (method vs full), model (the model-matched counterpart vs full) and "
                "approximation (method vs model-matched); --no-split: the counterpart alone")
      ->capture_default_str();
  cmd->add_option("--seeds", *seeds,
                  "render the method with N seeds (seed, seed + 3, …) against the one counterpart and "
                  "report every error metric's mean and standard deviation over them (stem.json's "
                  "\"seeds\"); the images written are the first seed's")
      ->check(CLI::Range(1, 1000))
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
    const Comparison c =
        compareWithCounterpart(*opt, *refSpp, *diffOptions, *reference,
                               *exactDevice == "cpu" ? ExactDevice::Cpu : ExactDevice::Same, *split, *seeds);
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
    std::vector<std::string> channels = {"image"};
    channels.insert(channels.end(), c.counterpart.aovs.begin(), c.counterpart.aovs.end());
    const std::string header = diffHeader(diffOptions->flip != FlipMode::Off);
    if (!c.split) {
      std::printf("  %-10s%s\n", "channel", header.c_str());
      for (auto& name : channels)
        std::printf("  %-10s%s\n", name.c_str(), diffLine(c.errors.at(name)).c_str());
    } else {
      std::printf("  full reference: %s %s, %d spp, seed %u, on the %s\n",
                  c.fullChoice.counterpart.method.c_str(), joined(c.fullChoice.counterpart.set).c_str(),
                  c.refSpp, c.fullSeed, c.fullChoice.device == "gl" ? "GL device" : "CPU");
      if (!c.fullChoice.note.empty()) std::printf("  note: %s\n", c.fullChoice.note.c_str());
      std::printf("  %-10s%-8s%s\n", "channel", "error", header.c_str());
      for (auto& name : channels) {
        std::printf("  %-10s%-8s%s\n", name.c_str(), "total", diffLine(c.totalErrors.at(name)).c_str());
        std::printf("  %-10s%-8s%s\n", "", "model", diffLine(c.modelErrors.at(name)).c_str());
        std::printf("  %-10s%-8s%s\n", "", "approx", diffLine(c.errors.at(name)).c_str());
      }
      std::printf(
          "  (total: %s vs full; model: the model-matched counterpart vs full; approx: %s vs the "
          "model-matched counterpart)\n",
          opt->method.c_str(), opt->method.c_str());
    }
    if (c.runs.size() > 1) printSeedTable(c, channels);
    std::printf(
        "  time: %s %.1f ms per frame + %.0f ms set-up (%d frames, timed passes; wall %.0f ms) on %s\n",
        opt->method.c_str(), perFrame, setup, frames, approx.stats["wall_ms"].get<double>(),
        approx.stats["gl_renderer"].get<std::string>().c_str());
    if (exact.stats.contains("total_ms") && exact.stats.contains("wall_ms"))
      std::printf("        exact %.0f ms (wall %.0f ms)%s\n", exact.stats["total_ms"].get<double>(),
                  exact.stats["wall_ms"].get<double>(), reference->empty() ? "" : ", when it was rendered");
    else
      std::printf("        exact: the reference image %s\n", reference->c_str());
    if (c.split)
      std::printf("        full %.0f ms (wall %.0f ms)\n", c.full.stats["total_ms"].get<double>(),
                  c.full.stats["wall_ms"].get<double>());
    std::fflush(stdout);
    std::fprintf(stderr, "wrote %s and %zu image/stat files\n", json.c_str(), files.size() - 1);
    if (c.interrupted) throw Interrupted{};
  });
}

}  // namespace vgi::app
