// vgi sweep: experiments/sweep.h — an experiment file expanded into independent
// `vgi render` processes (run here one after another, or printed for a batch
// system), and the results collected into DIR/results.csv and results.json.
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "apps/commands.h"
#include "core/error.h"
#include "core/shader_library.h"
#include "experiments/sweep.h"

namespace vgi::app {

void addSweepCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "sweep", "Run an experiment file: every method x parameter point against its reference, error vs time");
  auto file = std::make_shared<std::string>();
  auto dir = std::make_shared<std::string>();
  auto print = std::make_shared<bool>(false);
  auto collect = std::make_shared<bool>(false);
  auto pending = std::make_shared<bool>(false);
  cmd->add_option("experiment", *file, "the experiment file (JSON; see experiments/sweep.h)")->required();
  cmd->add_option("-o,--output", *dir, "the output folder (renders, results.csv, results.json)")->required();
  cmd->add_flag("--print-commands", *print,
                "print one vgi command per reference and point (for GNU parallel or a job array) and render "
                "nothing");
  cmd->add_flag("--pending", *pending,
                "like --print-commands, but only the renders not done yet in DIR (what a batch system "
                "still has to run; a killed or failed render is listed again)");
  cmd->add_flag("--collect", *collect, "render nothing: collect the results of whatever finished in DIR");
  cmd->callback([=] {
    if (int(*print) + int(*collect) + int(*pending) > 1)
      fail("--print-commands, --pending and --collect: give one of them");
    const Experiment e = loadExperiment(*file, *dir);
    std::error_code ec;
    std::string self = std::filesystem::read_symlink("/proc/self/exe", ec).string();
    if (ec || self.empty()) self = "vgi";
    // The renders' folders are made here, so each printed command runs as it is (nothing renders).
    auto printCommand = [&](const SweepRender& r) {
      std::filesystem::create_directories(r.dir);
      std::printf("%s\n", sweepCommand(r, self).c_str());
    };
    if (*print) {
      for (const auto* list : {&e.references, &e.curves})
        for (auto& r : *list)
          if (!r.args.empty()) printCommand(r);
      for (auto& p : e.points) printCommand(p.render);
      return;
    }
    if (*pending) {
      for (auto& [r, spp] : pendingRenders(e)) printCommand(*r);
      return;
    }
    if (!*collect) {
      try {
        runSweep(e, self);
      } catch (const SweepInterrupted& ex) {
        std::fprintf(stderr, "%s\n", ex.what());
        throw Interrupted{};
      }
    }
    const nlohmann::json rows = writeSweepResults(e);
    std::fprintf(stderr, "sweep %s: %zu points, %zu rows: wrote %s/results.csv and results.json\n",
                 e.name.c_str(), e.points.size(), rows.size(), e.dir.c_str());
    // The plots, Pareto tables and HTML report (Debian's python3 with python3-matplotlib).
    const std::string script =
        (std::filesystem::path(defaultShaderDir()).parent_path() / "scripts" / "sweep_report.py").string();
    if (!std::filesystem::is_regular_file(script))
      fail("sweep: the report script '", script,
           "' is missing (it lives in scripts/ beside the shader folder; VGI_SHADER_DIR moves both); the "
           "results are written: run scripts/sweep_report.py ",
           e.dir, " by hand");
    const std::string python = std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
    const std::string report = python + " '" + script + "' '" + e.dir + "' 2>&1";
    if (std::system(report.c_str()) != 0) {
      // Say why only when that is why: a script that failed on its input is not a missing package.
      const bool haveMatplotlib =
          std::system((python + " -c 'import matplotlib' >/dev/null 2>&1").c_str()) == 0;
      fail("sweep: the report (", script, ") failed",
           haveMatplotlib ? " (its output is above)"
                          : ": it needs python3-matplotlib (scripts/setup.sh installs it), which is missing",
           "; the results are written: ", e.dir, "/results.json and results.csv");
    }
    std::fprintf(stderr, "sweep %s: wrote the plots, pareto.md / pareto.tex and %s/report.html\n",
                 e.name.c_str(), e.dir.c_str());
  });
}

}  // namespace vgi::app
