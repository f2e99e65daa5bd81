// vgi render: one image of a scene with a method.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>

#include "apps/commands.h"
#include "core/error.h"
#include "core/json_text.h"
#include "core/params.h"
#include "core/progress.h"
#include "illum/run/method_help.h"
#include "illum/run/render_job.h"
#include "illum/run/render_outputs.h"

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
  cmd->add_option("--gl", args.gl,
                  "GL backend: auto|egl|osmesa|zink (zink: GL on Vulkan on lavapipe, the second CPU driver)")
      ->capture_default_str();
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

// The command's values as CLI11 fills them; options() resolves them into the render's options.
struct RenderCommand {
  RenderOptions opt;
  RenderArgs args;
  std::string out = "out.exr", stats, helpModule, aovs, checkpoints, job;
  float exposure = 1.0f;
  bool printJob = false, markdown = false;
};

void addRenderOnlyOptions(CLI::App* cmd, RenderCommand& c) {
  cmd->add_option("--frames", c.opt.frames,
                  "render an animation of N frames from --time: <stem>_NNNN.exr/.png per frame, one "
                  "<stem>.json with per-frame stats")
      ->capture_default_str();
  cmd->add_option("--time-step", c.opt.timeStep, "time between frames")->capture_default_str();
  cmd->add_option("-o,--output", c.out, "output image (.exr or .png; both are written, plus .json)")
      ->capture_default_str();
  cmd->add_option("--stats", c.stats, "also write the stats JSON here");
  cmd->add_option("--exposure", c.exposure, "PNG exposure multiplier")->capture_default_str();
  cmd->add_option("--aov", c.aovs,
                  "extra outputs, comma-separated (e.g. indirect,direct): <stem>.<aov>.exr/.png");
  cmd->add_option("--help-module", c.helpModule,
                  "print a method's parameters (or 'all': every method's) and exit; defaults that depend on "
                  "the scene are --scene's");
  cmd->add_flag("--markdown", c.markdown, "--help-module as Markdown (docs/PARAMETERS.md is 'all')");
  cmd->add_option("--job", c.job,
                  "the render's options from a job JSON (or a render's stats JSON: its \"job\"); no other "
                  "render option may be given with it");
  cmd->add_flag("--print-job", c.printJob, "print the job these options make (JSON) and exit");
  cmd->add_option(
      "--checkpoints", c.checkpoints,
      "sample counts (comma-separated, e.g. 1,4,16,64) at which the image so far and its stats are "
      "written too: <stem>.sppNNNNN.exr/.png/.json (convergence plots)");
  cmd->add_option("--time-limit", c.opt.timeLimitS,
                  "seconds: stop accumulating once the render (set-up included) has taken this long, after "
                  "at least one sample; --spp is then the most samples (equal-time comparisons)");
}

// The render's options: from --job, or from the flags.
RenderOptions resolveOptions(const CLI::App* cmd, const RenderCommand& c) {
  if (!c.job.empty()) {
    for (const CLI::Option* o : cmd->get_options())
      if (o->count() > 0 && !kJobCompanions.count(o->get_name()))
        fail("--job '", c.job, "' gives the render's options: ", o->get_name(), " may not be given with it");
    return readRenderJob(readJsonFile(c.job, "--job"), "'" + c.job + "'");
  }
  RenderOptions opt = c.opt;
  applyRenderArgs(c.args, opt);
  opt.aovs = splitList(c.aovs);
  for (auto& k : splitList(c.checkpoints)) {
    char* end = nullptr;
    const long v = std::strtol(k.c_str(), &end, 10);
    if (k.empty() || *end || k.size() > 9) fail("--checkpoints: '", k, "' is not a sample count");
    opt.checkpoints.push_back(int(v));  // runRender checks the range against --spp
  }
  opt.methodGiven = cmd->count("--method") > 0;
  return opt;
}

bool samePath(const std::string& a, const std::string& b) {
  return std::filesystem::weakly_canonical(a) == std::filesystem::weakly_canonical(b);
}

// -o and --stats can be written, and --stats is none of the render's other files. The render's own
// stats (-o a.exr writes a.json) may be named: that file holds the stats already (and its list of
// outputs), so --stats then writes nothing more.
void checkOutputs(const RenderCommand& c, const RenderOptions& opt) {
  checkOutputPath(c.out);
  if (c.stats.empty()) return;
  checkOutputFile(c.stats, "--stats");
  const std::vector<std::string> own = renderOutputNames(c.out, opt);  // the stats JSON first
  for (size_t i = 1; i < own.size(); ++i)
    if (samePath(own[i], c.stats))
      fail("--stats '", c.stats, "' is also a file this render writes for -o '", c.out, "' (", own[i],
           "): give another path");
}

// A still: its checkpoints as they come, then the image; `files` lists what was written.
RenderOutput renderStill(const RenderOptions& opt, const RenderCommand& c, std::vector<std::string>& files) {
  RenderOutput result = runRender(opt, {}, [&](int spp, const RenderOutput& k) {
    for (auto& file : writeCheckpointOutputs(k, c.out, spp, c.exposure)) files.push_back(file);
  });
  if (result.result.sppCompleted == 0) {
    std::fprintf(stderr, "interrupted before the first sample of every pixel was done: nothing written\n");
    throw Interrupted{};
  }
  std::vector<std::string> last = writeRenderOutputs(result, c.out, c.exposure);
  files.insert(files.begin(), last.begin(), last.end());
  if (result.result.interrupted)
    std::fprintf(stderr, "interrupted: wrote %d of %d samples per pixel\n", result.result.sppCompleted,
                 opt.spp);
  if (result.result.timeLimited)
    std::fprintf(stderr, "--time-limit %g s reached after %d of %d samples per pixel\n", opt.timeLimitS,
                 result.result.sppCompleted, opt.spp);
  std::fprintf(stderr, "%s %s %dx%d %d spp: %.1f ms (%s)\n", opt.method.c_str(), opt.scene.c_str(), opt.width,
               opt.height, result.result.sppCompleted, result.stats["wall_ms"].get<double>(),
               result.stats["gl_renderer"].get<std::string>().c_str());
  return result;
}

// An animation: each frame written as soon as it is done (an interrupted one keeps its frames), then
// one stats JSON.
RenderOutput renderAnimation(const RenderOptions& opt, const RenderCommand& c,
                             std::vector<std::string>& files) {
  RenderOutput result = runRender(opt, [&](int frame, const RenderOutput& f) {
    for (auto& file : writeFrameImages(f, c.out, frame, c.exposure)) files.push_back(file);
  });
  files.insert(files.begin(), writeAnimationStats(result, c.out, files, c.exposure));
  const int done = result.stats["frames_completed"].get<int>();
  if (result.stats["interrupted"].get<bool>())
    std::fprintf(stderr, "interrupted: wrote %d of %d frames\n", done, opt.frames);
  std::fprintf(stderr, "%s %s %dx%d %d spp, %d frames: %.1f ms (%s)\n", opt.method.c_str(), opt.scene.c_str(),
               opt.width, opt.height, opt.spp, done, result.stats["wall_ms"].get<double>(),
               result.stats["gl_renderer"].get<std::string>().c_str());
  return result;
}

void runRenderCommand(const CLI::App* cmd, const RenderCommand& c) {
  if (!c.helpModule.empty()) {
    const std::string help = c.markdown ? describeMethodsMarkdown(c.helpModule, c.opt.scene)
                                        : describeMethod(c.helpModule, c.opt.scene);
    std::fputs(help.c_str(), stdout);
    return;
  }
  if (c.markdown) fail("--markdown goes with --help-module NAME|all");
  if (!(c.exposure > 0.0f) || c.exposure > 1e6f) fail("--exposure ", c.exposure, ": must be in (0, 1e6]");
  const RenderOptions opt = resolveOptions(cmd, c);
  if (c.printJob) {
    checkRenderJob(opt);  // only a job `vgi render --job` renders
    std::printf("%s\n", jsonText(renderJobJson(opt), 2).c_str());
    return;
  }
  checkOutputs(c, opt);
  installInterruptHandler();
  std::vector<std::string> files;
  const RenderOutput result = opt.frames == 1 ? renderStill(opt, c, files) : renderAnimation(opt, c, files);
  if (!c.stats.empty() && !samePath(c.stats, renderOutputNames(c.out, opt).front()))
    writeJsonFile(result.stats, c.stats);
  if (opt.frames > 1) {
    std::fprintf(stderr, "wrote %s and %zu frame files\n", files[0].c_str(), files.size() - 1);
    if (result.stats["interrupted"].get<bool>()) throw Interrupted{};
    return;
  }
  for (auto& f : files) std::fprintf(stderr, "wrote %s\n", f.c_str());
  if (result.result.interrupted) throw Interrupted{};
}

}  // namespace

void addRenderCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("render", "Render a scene with a method to EXR + PNG + JSON stats");
  auto c = std::make_shared<RenderCommand>();
  c->opt.method = defaultMethodName();
  c->args.size = "512x512";
  addRenderOptions(cmd, c->opt, c->args);
  addRenderOnlyOptions(cmd, *c);
  cmd->callback([cmd, c] { runRenderCommand(cmd, *c); });
}

}  // namespace vgi::app
