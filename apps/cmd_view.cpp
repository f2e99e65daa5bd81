// vgi view: apps/viewer.h — the interactive viewer, and its headless contract
// (--frames N --screenshot FILE, --script, --record) for scripts and tests.
#include "apps/commands.h"
#include "apps/viewer.h"
#include "core/error.h"

namespace vgi::app {

void addViewCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "view",
      "Interactive viewer: any GL method every frame, parameter panel, per-pass timings (GLFW + ImGui)");
  auto opt = std::make_shared<ViewOptions>();
  auto args = std::make_shared<RenderArgs>();
  opt->render.method = defaultMethodName();
  opt->render.spp = 1 << 16;
  args->size = "768x768";
  addRenderOptions(cmd, opt->render, *args);
  cmd->add_option(
         "--frames", opt->frames,
         "headless: render N frames (accumulating, as vgi render --spp N does), write --screenshot, exit")
      ->check(CLI::Range(1, 1 << 20));
  cmd->add_option("--screenshot", opt->screenshot,
                  "write the accumulation at the end (EXR + PNG + the stats JSON of vgi render)");
  cmd->add_option("--script", opt->script, "replay a JSON list of events (apps/viewer.h), then exit");
  cmd->add_option("--record", opt->record, "write every shown frame as DIR/frame_NNNNN.png");
  cmd->add_option("--exposure", opt->exposure, "display and PNG exposure")->capture_default_str();
  cmd->callback([=] {
    if (!(opt->exposure > 0.0f) || opt->exposure > 1e6f)
      fail("--exposure ", opt->exposure, ": must be in (0, 1e6]");
    applyRenderArgs(*args, opt->render);
    opt->render.methodGiven = cmd->count("--method") > 0;
    if (opt->frames == 0 && !opt->screenshot.empty() && opt->script.empty())
      fail(
          "--screenshot needs --frames N (or a --script): the interactive viewer writes screenshots with "
          "F12");
    const int rc = runViewer(*opt);
    if (rc != 0) throw ExitCode{rc};
  });
}

}  // namespace vgi::app
