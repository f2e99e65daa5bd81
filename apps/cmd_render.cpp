// vgi render: one image of a scene with a method.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>

#include "apps/commands.h"
#include "core/error.h"
#include "core/json_text.h"
#include "core/progress.h"
#include "illum/framework/render_job.h"

namespace vgi::app {

void addRenderOptions(CLI::App* cmd, RenderOptions& opt, RenderArgs& args) {
  cmd->add_option("--scene", opt.scene, "builtin:cornell, a scene .json, or an .obj/.gltf/.glb/.ply file")
      ->capture_default_str();
  cmd->add_option("--method", opt.method, "rendering method (see vgi render --help-module NAME)")
      ->capture_default_str();
  cmd->add_option("--set", opt.set, "method parameter key=value (repeatable)");
  cmd->add_option("--preset", opt.preset, "apply a named parameter preset from the scene file first");
  cmd->add_option("--size", args.size, "image size WxH")->capture_default_str();
  cmd->add_option("--spp", opt.spp, "samples per pixel (GL methods: jittered frames)")->capture_default_str();
  cmd->add_option("--seed", opt.seed, "random seed")->capture_default_str();
  cmd->add_option("--threads", opt.threads, "CPU threads (0 = all cores)")->capture_default_str();
  cmd->add_option("--time", opt.time, "animation time for dynamic meshes (of the first frame)")
      ->capture_default_str();
  cmd->add_option("--gl", args.gl, "GL backend: auto|egl|osmesa")->capture_default_str();
  cmd->add_option(
         "--accumulate", args.accumulate,
         "sample accumulation: compensated (Kahan sums on the GPU: no drift over 10^5 samples) or plain "
         "(one float add per sample)")
      ->capture_default_str();
  cmd->add_option("--camera", args.camera,
                  "replace the scene's camera: px,py,pz,tx,ty,tz,ux,uy,uz[,fov_y_deg] (a render's stats JSON "
                  "has it as camera.option)");
  cmd->add_option(
      "--light", args.lights,
      "place the scene's point or spot light I at x,y,z: I=x,y,z (repeatable; a render's stats JSON "
      "has each light's as lights[I].option)");
  cmd->add_flag("--quiet", args.quiet, "no progress bars");
}

void applyRenderArgs(const RenderArgs& args, RenderOptions& opt) {
  parseSize(args.size, opt.width, opt.height);
  opt.gl = parseGlBackend(args.gl);
  opt.progress = !args.quiet;
  if (!args.camera.empty()) opt.camera = parseCamera(args.camera);
  for (auto& l : args.lights) opt.lightPositions.push_back(parseLightPosition(l));
  if (args.accumulate == "compensated")
    opt.accumulation = Accumulation::Compensated;
  else if (args.accumulate == "plain")
    opt.accumulation = Accumulation::Plain;
  else
    fail("--accumulate '", args.accumulate, "': expected compensated or plain");
}

namespace {
// What may be given beside --job: where the outputs go, not what is rendered.
const std::set<std::string> kJobCompanions = {"--job", "--print-job", "--output", "--stats", "--exposure"};
}  // namespace

void addRenderCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("render", "Render a scene with a method to EXR + PNG + JSON stats");
  auto opt = std::make_shared<RenderOptions>();
  auto args = std::make_shared<RenderArgs>();
  auto out = std::make_shared<std::string>("out.exr");
  auto stats = std::make_shared<std::string>();
  auto helpModule = std::make_shared<std::string>();
  auto exposure = std::make_shared<float>(1.0f);
  opt->method = defaultMethodName();
  args->size = "512x512";
  addRenderOptions(cmd, *opt, *args);
  cmd->add_option(
         "--frames", opt->frames,
         "render an animation of N frames from --time: <stem>_NNNN.exr/.png per frame, one <stem>.json "
         "with per-frame stats")
      ->capture_default_str();
  cmd->add_option("--time-step", opt->timeStep, "time between frames")->capture_default_str();
  cmd->add_option("-o,--output", *out, "output image (.exr or .png; both are written, plus .json)")
      ->capture_default_str();
  cmd->add_option("--stats", *stats, "also write the stats JSON here");
  cmd->add_option("--exposure", *exposure, "PNG exposure multiplier")->capture_default_str();
  auto aovs = std::make_shared<std::string>();
  cmd->add_option("--aov", *aovs,
                  "extra outputs, comma-separated (e.g. indirect,direct): <stem>.<aov>.exr/.png");
  cmd->add_option("--help-module", *helpModule, "print a method's parameters and exit");
  auto job = std::make_shared<std::string>();
  auto printJob = std::make_shared<bool>(false);
  cmd->add_option("--job", *job,
                  "the render's options from a job JSON (or a render's stats JSON: its \"job\"); no other "
                  "render option may be given with it");
  cmd->add_flag("--print-job", *printJob, "print the job these options make (JSON) and exit");
  auto checkpoints = std::make_shared<std::string>();
  cmd->add_option(
      "--checkpoints", *checkpoints,
      "sample counts (comma-separated, e.g. 1,4,16,64) at which the image so far and its stats are "
      "written too: <stem>.sppNNNNN.exr/.png/.json (convergence plots)");
  cmd->add_option("--time-limit", opt->timeLimitS,
                  "seconds: stop accumulating once the render (set-up included) has taken this long, after "
                  "at least one sample; --spp is then the most samples (equal-time comparisons)");
  cmd->callback([=] {
    if (!helpModule->empty()) {
      std::printf("%s", describeMethod(*helpModule, opt->scene).c_str());
      return;
    }
    if (!(*exposure > 0.0f) || *exposure > 1e6f) fail("--exposure ", *exposure, ": must be in (0, 1e6]");
    if (!job->empty()) {
      for (const CLI::Option* o : cmd->get_options())
        if (o->count() > 0 && !kJobCompanions.count(o->get_name()))
          fail("--job '", *job, "' gives the render's options: ", o->get_name(), " may not be given with it");
      *opt = readRenderJob(readJsonFile(*job, "--job"), "'" + *job + "'");
    } else {
      applyRenderArgs(*args, *opt);
      opt->aovs = splitList(*aovs);
      for (auto& c : splitList(*checkpoints)) {
        char* end = nullptr;
        const long v = std::strtol(c.c_str(), &end, 10);
        if (c.empty() || *end || c.size() > 9) fail("--checkpoints: '", c, "' is not a sample count");
        opt->checkpoints.push_back(int(v));  // runRender checks the range against --spp
      }
      opt->methodGiven = cmd->count("--method") > 0;
    }
    if (*printJob) {
      checkRenderOptions(*opt);
      std::printf("%s\n", jsonText(renderJobJson(*opt), 2).c_str());
      return;
    }
    checkOutputPath(*out);
    if (!stats->empty()) {
      checkOutputFile(*stats, "--stats");
      // The stats JSON must not replace one of the render's own files.
      for (const std::string& f : renderOutputNames(*out, *opt))
        if (std::filesystem::weakly_canonical(f) == std::filesystem::weakly_canonical(*stats))
          fail("--stats '", *stats, "' is also a file this render writes for -o '", *out, "' (", f,
               "): give another path");
    }
    installInterruptHandler();
    std::vector<std::string> files;
    RenderOutput result;
    if (opt->frames == 1) {
      result = runRender(*opt, {}, [&](int spp, const RenderOutput& c) {
        for (auto& file : writeCheckpointOutputs(c, *out, spp, *exposure)) files.push_back(file);
      });
      if (result.result.sppCompleted == 0) {
        std::fprintf(stderr,
                     "interrupted before the first sample of every pixel was done: nothing written\n");
        throw Interrupted{};
      }
      std::vector<std::string> last = writeRenderOutputs(result, *out, *exposure);
      files.insert(files.begin(), last.begin(), last.end());
    } else {
      // Each frame is written as soon as it is done: an interrupted animation keeps its frames.
      result = runRender(*opt, [&](int frame, const RenderOutput& f) {
        for (auto& file : writeFrameImages(f, *out, frame, *exposure)) files.push_back(file);
      });
      files.insert(files.begin(), writeAnimationStats(result, *out, files, *exposure));
    }
    if (!stats->empty()) writeJsonFile(result.stats, *stats);
    if (opt->frames > 1) {
      if (result.stats["interrupted"].get<bool>())
        std::fprintf(stderr, "interrupted: wrote %d of %d frames\n",
                     result.stats["frames_completed"].get<int>(), opt->frames);
      std::fprintf(stderr, "%s %s %dx%d %d spp, %d frames: %.1f ms (%s)\n", opt->method.c_str(),
                   opt->scene.c_str(), opt->width, opt->height, opt->spp,
                   result.stats["frames_completed"].get<int>(), result.stats["wall_ms"].get<double>(),
                   result.stats["gl_renderer"].get<std::string>().c_str());
      std::fprintf(stderr, "wrote %s and %zu frame files\n", files[0].c_str(), files.size() - 1);
      if (result.stats["interrupted"].get<bool>()) throw Interrupted{};
      return;
    }
    if (result.result.interrupted)
      std::fprintf(stderr, "interrupted: wrote %d of %d samples per pixel\n", result.result.sppCompleted,
                   opt->spp);
    if (result.result.timeLimited)
      std::fprintf(stderr, "--time-limit %g s reached after %d of %d samples per pixel\n", opt->timeLimitS,
                   result.result.sppCompleted, opt->spp);
    std::fprintf(stderr, "%s %s %dx%d %d spp: %.1f ms (%s)\n", opt->method.c_str(), opt->scene.c_str(),
                 opt->width, opt->height, result.result.sppCompleted, result.stats["wall_ms"].get<double>(),
                 result.stats["gl_renderer"].get<std::string>().c_str());
    for (auto& f : files) std::fprintf(stderr, "wrote %s\n", f.c_str());
    if (result.result.interrupted) throw Interrupted{};
  });
}

}  // namespace vgi::app
