// `vgi bench traverse` (the measurement behind docs/BENCHMARKS.md's traversal tables): the tracers
// on the near-field ray population of a scene (traverse/ray_population.h) at one or more ray
// lengths: speed on the CPU threads and in GLSL where a tracer has a GLSL kernel, agreement with the
// DDA oracle and with Embree's exact hits, and what each ray costs counted by the C++ build of the
// shared kernels (steps, loads, bytes, levels climbed and refined: mean and 99th percentile).
#pragma once
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

namespace vgi {

// The bench's settings, as `vgi bench traverse` names them (--scene, --voxels, …; maxDist is
// --max-dist's comma-separated list of fractions of the diagonal or "inf").
struct TraverseBenchOptions {
  std::string scene = "builtin:cornell", voxels = "256", voxelizer = "atlas",
              tracers = "hierarchical,dda,march,bvh,embree", maxDist = "0.1", gl = "auto";
  size_t rays = 1000000;
  int threads = 0, repeat = 3;
  uint32_t seed = 1;
  float offset = 1.0f;
  unsigned bvhWidth = 2;
  bool noGl = false;
};

// Checks the settings (refusing a bad one by its option's name), builds the grid, its pyramid and the
// BVHs, and traces every length: the results as JSON (one entry per length under "lengths"; with one
// length its fields also at the top; with several, where GLSL hierarchical and bvh cross).
nlohmann::json runTraverseBench(const TraverseBenchOptions& o);

// The results as the tables `vgi bench traverse` prints.
void printTraverseBench(const nlohmann::json& s);

}  // namespace vgi
