// `vgi sweep`, the renders run: every reference, curve and point whose stats do not say it is done,
// one `vgi render` process at a time (experiments/sweep.h), and the listing of those still to run.
#include <sys/wait.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/json_fields.h"
#include "core/json_text.h"
#include "core/output_files.h"
#include "core/warnings.h"
#include "experiments/sweep_detail.h"
#include "illum/run/render_job.h"
#include "illum/run/render_outputs.h"

namespace vgi {

namespace fs = std::filesystem;

namespace sweep_detail {

std::string stemOfRender(const SweepRender& r) { return fs::path(r.stem).replace_extension("").string(); }

nlohmann::json readJson(const std::string& path) {
  try {
    return readJsonFile(path, "stats");
  } catch (const Error&) {
    return nullptr;  // not there yet, or a render killed while writing it
  }
}

void notDone(const Error& e) {
  printWarning(std::string(e.what()) + ": that render counts as not done (vgi sweep renders it again)");
}

}  // namespace sweep_detail

using sweep_detail::kMaxSpp;
using sweep_detail::notDone;
using sweep_detail::readJson;
using sweep_detail::stemOfRender;

std::string sweepCommand(const SweepRender& r, const std::string& vgi) {
  std::string c = shellQuote(vgi);
  for (auto& a : r.args) c += " " + shellQuote(a);
  return c;
}

bool sweepRenderDone(const SweepRender& r, int spp) {
  if (!r.file.empty()) return true;
  const std::string path = stemOfRender(r) + ".json";
  const nlohmann::json s = readJson(path);
  if (s.is_null()) return false;
  try {
    const JsonFields f(s, "'" + path + "'");
    if (r.options.frames > 1) {  // every frame with every sample
      const nlohmann::json& frames = f.array("frames");
      if (f.flag("interrupted", true) || int(frames.size()) != r.options.frames) return false;
      const JsonFields last(frames.back(),
                            "'" + path + "' frames[" + std::to_string(frames.size() - 1) + "]");
      return last.integer("spp_completed", 0, 0, kMaxSpp) >= spp;
    }
    return f.integer("spp_completed", 0, 0, kMaxSpp) >= spp || f.flag("time_limited", false);
  } catch (const Error& e) {
    notDone(e);
    return false;
  }
}

std::string sweepFrameStem(const SweepRender& r, int frame) {
  return r.options.frames > 1 ? frameStem(stemOfRender(r), frame) : stemOfRender(r);
}

int sweepRenderSpp(const SweepRender& r) { return r.args.empty() ? 1 : r.options.spp; }

std::vector<std::pair<const SweepRender*, int>> pendingRenders(const Experiment& e) {
  std::vector<std::pair<const SweepRender*, int>> todo;
  for (const auto* list : {&e.references, &e.curves})
    for (auto& r : *list)
      if (!r.args.empty() && !sweepRenderDone(r, sweepRenderSpp(r))) todo.emplace_back(&r, sweepRenderSpp(r));
  for (auto& p : e.points)
    if (!sweepRenderDone(p.render, p.spp)) todo.emplace_back(&p.render, p.spp);
  return todo;
}

int runSweep(const Experiment& e, const std::string& vgi) {
  const std::vector<std::pair<const SweepRender*, int>> todo = pendingRenders(e);
  int n = 0;
  std::vector<std::string> failed;
  for (auto& [r, spp] : todo) {
    fs::create_directories(r->dir);
    const std::string cmd = sweepCommand(*r, vgi);
    writeTextFile(cmd + "\n", r->dir + "/command.txt");
    std::fprintf(stderr, "sweep %s: [%d/%zu] %s\n", e.name.c_str(), ++n, todo.size(), r->id.c_str());
    const int rc = std::system((cmd + " > " + shellQuote(r->dir + "/log.txt") + " 2>&1").c_str());
    if ((WIFSIGNALED(rc) && (WTERMSIG(rc) == SIGINT || WTERMSIG(rc) == SIGTERM)) ||
        (WIFEXITED(rc) && WEXITSTATUS(rc) == 130))
      throw SweepInterrupted("sweep: interrupted during " + r->id + " (" + std::to_string(n - 1) + " of " +
                             std::to_string(todo.size()) + " renders done); run it again to resume");
    // The render's warnings reach the person running the sweep (once each), its error the failure list.
    std::string error;
    std::ifstream log(r->dir + "/log.txt");
    for (std::string line; std::getline(log, line);) {
      if (line.rfind("vgi: warning: ", 0) == 0) printWarning(line.substr(14));
      if (line.rfind("vgi: error: ", 0) == 0) error = ": " + line.substr(5);
    }
    if (rc != 0 || !sweepRenderDone(*r, spp))
      failed.push_back(r->id + error + " (see " + r->dir + "/log.txt)");
  }
  if (!failed.empty()) {
    std::string list;
    for (auto& f : failed) list += "\n  " + f;
    fail("sweep: ", failed.size(), " of ", todo.size(), " renders failed:", list);
  }
  return n;
}

}  // namespace vgi
