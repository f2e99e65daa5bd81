// vgi bench: measured comparisons that go into docs/BENCHMARKS.md. This file only parses; the
// benchmarks live in experiments/ beside the sweep.
//   traverse  the tracers on the near-field ray population of a scene: speed
//             (CPU threads, and GLSL where it runs) against agreement with the
//             DDA oracle and with exact Embree hits (experiments/traverse_bench.h).
//   motion    the cost of one moving object per frame, pass by pass: two animations' stats
//             (experiments/motion_cost.h).
#include <cstdio>
#include <nlohmann/json.hpp>

#include "apps/commands.h"
#include "core/json_text.h"
#include "core/output_files.h"
#include "experiments/motion_cost.h"
#include "experiments/traverse_bench.h"

namespace vgi::app {

namespace {

void addTraverseBench(CLI::App& bench) {
  auto* cmd =
      bench.add_subcommand("traverse", "Tracers on the near-field ray population: speed against agreement");
  auto o = std::make_shared<TraverseBenchOptions>();
  auto json = std::make_shared<bool>(false);
  auto stats = std::make_shared<std::string>();
  cmd->add_option("--scene", o->scene, "builtin:cornell, a scene .json, or a model file")
      ->capture_default_str();
  cmd->add_option("--voxels", o->voxels, "N (N×N×N) or WxHxD")->capture_default_str();
  cmd->add_option("--voxelizer", o->voxelizer, "which voxelizer builds the grid")->capture_default_str();
  cmd->add_option("--tracers", o->tracers, "comma-separated tracers to run")->capture_default_str();
  cmd->add_option("--rays", o->rays, "number of rays (per ray length)")->capture_default_str();
  cmd->add_option("--max-dist", o->maxDist,
                  "ray length as a fraction of the scene diagonal, or 'inf'; a comma-separated list sweeps "
                  "the lengths and reports where GLSL hierarchical and bvh cross")
      ->capture_default_str();
  cmd->add_option("--offset", o->offset, "ray start offset along the normal, in voxel diagonals")
      ->capture_default_str();
  cmd->add_option("--threads", o->threads, "CPU threads (0 = all cores)")->capture_default_str();
  cmd->add_option("--repeat", o->repeat, "timed CPU runs per tracer (the fastest counts)")
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "ray population seed")->capture_default_str();
  cmd->add_option("--gl", o->gl,
                  "GL backend: auto|egl|osmesa|zink (zink: GL on Vulkan on lavapipe, the second CPU driver)")
      ->capture_default_str();
  cmd->add_option("--bvh-width", o->bvhWidth,
                  "children per node of the bvh tracer's BVH: 2 (Aila & Laine, the methods' layout) or 4")
      ->check(CLI::IsMember({2u, 4u}))
      ->capture_default_str();
  cmd->add_flag("--no-gl", o->noGl, "skip the GLSL runs (the voxelizer may still need GL)");
  cmd->add_flag("--json", *json, "print the results as JSON instead of a table");
  cmd->add_option("--stats", *stats, "also write the JSON here");
  cmd->callback([o, json, stats] {
    if (!stats->empty()) checkOutputFile(*stats, "--stats");
    const nlohmann::json s = runTraverseBench(*o);
    if (!stats->empty()) writeJsonFile(s, *stats);
    if (*json)
      std::printf("%s\n", jsonText(s, 2).c_str());
    else
      printTraverseBench(s);
  });
}

void addMotionBench(CLI::App& bench) {
  auto* cmd =
      bench.add_subcommand("motion",
                           "The cost of motion: per pass and frame, an animation with a moving object (its "
                           "stats JSON) against the "
                           "same scene standing still, from two `vgi render --frames N` runs of one method");
  auto moving = std::make_shared<std::string>(), still = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("MOVING", *moving, "stats JSON of the animation with the object moving")->required();
  cmd->add_option("STILL", *still, "stats JSON of the same animation with it standing still")->required();
  cmd->add_flag("--json", *json, "print JSON");
  cmd->callback([=] {
    const MotionCost c =
        motionCost(readJsonFile(*moving, "MOVING"), readJsonFile(*still, "STILL"), *moving, *still);
    if (*json) {
      nlohmann::json j = c.toJson();
      j["moving"] = *moving;
      j["still"] = *still;
      std::printf("%s\n", jsonText(j, 2).c_str());
      return;
    }
    std::fputs(c.table().c_str(), stdout);
  });
}

}  // namespace

void addBenchCommand(CLI::App& app) {
  auto* bench = app.add_subcommand("bench", "Benchmarks (numbers for docs/BENCHMARKS.md)");
  bench->require_subcommand(1);
  addTraverseBench(*bench);
  addMotionBench(*bench);
}

}  // namespace vgi::app
