// `vgi sweep`: an experiment file (scenes, image size, methods with parameter
// grids, checkpoints, the reference) expanded into independent `vgi render`
// processes, each writing EXR + JSON into the output folder, and the results
// collected from whatever finished: every point's error at every checkpoint
// against its reference, with the time spent to reach it.
//
// Experiment file (JSON; every key is checked, unknown keys are errors):
//   {
//     "name": "smoke",                       // optional
//     "scenes": ["builtin:cornell"],          // one or more
//     "size": "32x32",
//     "spp": 16, "checkpoints": [1, 4],       // checkpoints below spp (optional)
//     "seed": 1,                              // optional (1)
//     "aovs": ["indirect"],                   // channels compared besides the image (optional)
//     "epsilon": 0.01, "relative_epsilon": 0.1,   // relMSE's ε and the relative one (optional)
//     "reference": {"spp": 256}               // each method's registry counterpart (default),
//                | {"method": "reference", "set": {"integrator": "ao"}, "spp": 256}
//                | {"file": "ref.exr"}        // an existing image (one scene; its AOVs next to it)
//     "methods": [ {"method": "nearfield", "label": "NF",
//                   "set": {"shadow_res": 256},             // fixed parameters
//                   "grid": {"voxels": [64, 128], "rays": [4, 16]}} ]   // every combination
//   }
// Layout of the output folder DIR: DIR/references/<id>/ref.*, DIR/points/<id>/render.*
// (plus render.sppNNNNN.* per checkpoint) and command.txt in each; a render is
// done when its JSON says every sample completed (a killed one is run again).
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/image_metrics.h"

namespace vgi {

struct SweepRender {
  std::string id;                 // stable: a hash of its arguments
  std::string dir;                // DIR/points/<id> or DIR/references/<id>
  std::string stem;               // dir/render.exr or dir/ref.exr
  std::vector<std::string> args;  // `vgi` arguments (render …)
  std::string file;               // a reference given as an existing image (no args)
};

struct SweepPoint {
  SweepRender render;
  std::string scene, method, label;
  nlohmann::json params;  // the grid's values of this point, key → value (text)
  size_t reference = 0;   // index into Experiment::references
};

struct Experiment {
  std::string name, path, dir;
  std::vector<std::string> scenes;
  int width = 0, height = 0, spp = 0;
  uint32_t seed = 1;
  std::vector<int> checkpoints;   // sorted, < spp
  std::vector<std::string> aovs;  // besides the image
  DiffOptions diff;               // relMSE's ε (absolute)
  double relativeEpsilon = 0.1;   // the second relMSE's relative ε
  std::vector<SweepRender> references;
  std::vector<SweepPoint> points;
};

// Reads and checks the file, expanding the grids into points, before anything
// renders: unknown keys, methods or parameters, empty grids, out-of-range
// values, a reference image of another size, an unwritable DIR are refused
// naming the key and value.
Experiment loadExperiment(const std::string& path, const std::string& dir);

// The shell command of a render (`vgi` = the binary's path), quoted.
std::string sweepCommand(const SweepRender& r, const std::string& vgi);
// Whether a render finished (its JSON has every sample).
bool sweepRenderDone(const SweepRender& r, int spp);
// Runs every reference and point not done yet, one process at a time; returns
// how many ran. Prints progress lines to stderr.
int runSweep(const Experiment& e, const std::string& vgi);

// One row per point and checkpoint, for whatever finished: the point's scene,
// method, label, parameters, spp, time (total, per-sample passes, set-up) and
// per channel relMSE (ε and relative ε), rel. MAE, SSIM and energy against its
// reference, plus GL_RENDERER, machine, git revision.
nlohmann::json collectSweep(const Experiment& e);
// Writes DIR/results.json and DIR/results.csv from collectSweep's rows;
// returns the rows.
nlohmann::json writeSweepResults(const Experiment& e);

}  // namespace vgi
