// `vgi sweep`: an experiment file (scenes, image size, methods with parameter
// grids, checkpoints, the reference) expanded into independent `vgi render`
// processes, each writing EXR + JSON into the output folder, and the results
// collected from whatever finished: every point's error at every checkpoint
// against its reference, with the time spent to reach it.
//
// Experiment file (JSON; every key is checked, unknown keys are errors):
//   {
//     "name": "smoke",                       // optional
//     "scenes": ["builtin:cornell",           // one or more: a scene, or an animation of one
//                {"scene": "scenes/cornell-bunny.json", "frames": 6, "time_step": 0.1, "time": 0}],
//     "size": "32x32",
//     "spp": 16, "checkpoints": [1, 4],       // checkpoints below spp (optional)
//     "seed": 1,                              // optional (1)
//     "seeds": 4,                             // optional (1): each point renders with this many
//                                             // seeds (seed + 3k, compare.h kSeedStride), a row
//                                             // each ("seed"), against the one reference: the
//                                             // report's mean ± standard deviation over them
//     "aovs": ["indirect"],                   // channels compared besides the image (optional)
//     "epsilon": 0.01, "relative_epsilon": 0.1,   // relMSE's ε and the relative one (optional)
//     "dark_tolerance": 0,                    // the leak's dark pixels: reference ≤ this × its mean
//                                             // (core/image_metrics.h; optional, 0 = exactly dark)
//     "flip": "auto",                         // FLIP per channel (core/flip.h): auto (HDR and LDR),
//                                             // ldr, hdr or off (optional, auto)
//     "time_budget_s": 10,                    // optional: every point stops after this wall time
//                                             // (`vgi render --time-limit`; spp is then the most)
//     "frames": 6, "time_step": 0.1, "time": 0,   // optional: the scenes' default animation
//                                             // (`vgi render --frames`; 1 frame: a still). An
//                                             // animation's row holds its frames' mean static
//                                             // metrics, the temporal ones (core/image_metrics.h:
//                                             // temporal_error, change, change_reference) and its
//                                             // times per frame; with an animation the experiment
//                                             // has no checkpoints, curves or time budget
//     "reference": {"spp": 256,               // each method's registry counterpart (default),
//                   "convergence": [1, 4, 16],   // optional: the counterpart's own curve (next seed)
//                                             // at these counts → each row's equal-error time ratio
//                   "split": true,            // optional: also the full reference (the registry's
//                                             // Counterpart::full, seed + 2) of each point whose
//                                             // reference is its model-matched counterpart; rows
//                                             // then carry per channel total_* (the point against
//                                             // it) and model_* (the counterpart against it)
//                   "device": "same"}         // optional: the curve runs on each method's device
//                                             // (a GL method's: reference_gl) — or "cpu": the
//                                             // CPU counterpart (a reference_gl reference's curve
//                                             // runs `reference`); the reference image is the
//                                             // registry's (or the given method's) either way.
//                                             // Left out: the method's device where the twin takes
//                                             // the parameters, else the CPU; "same" written out is
//                                             // refused where it cannot be done. Each curve's row
//                                             // says where it ran ("device", "same_device", "note")
//                | {"method": "reference", "set": {"integrator": "ao"}, "spp": 256}
//                | {"file": "ref.exr"}        // an existing image (one scene; its AOVs next to it)
//     "methods": [ {"method": "nearfield", "label": "NF",
//                   "set": {"shadow_res": 256},             // fixed parameters
//                   "grid": {"voxels": [64, 128], "rays": [4, 16]},   // every combination
//                   "spp": 512,                           // optional: this method's samples
//                   "seed": 2,                            // optional: its seed (the experiment's;
//                                                         // the reference keeps the experiment's:
//                                                         // an exact method with another seed
//                                                         // measures the reference's noise floor)
//                   "reference": {"counterpart_of": "nearfield"}   // optional: its own reference,
//                              | {"method": "reference", "set": {…}}   // (spp: the experiment's)
//                              | {"variant": {"visibility": "exact"}}} ]  // the point itself with these
//                                             // parameters changed (an error split by stage)
//   }
// Layout of the output folder DIR: DIR/references/<id>/ref.*, DIR/curves/<id>/render.* (the
// counterparts' convergence renders), DIR/points/<id>/render.*
// (plus render.sppNNNNN.* per checkpoint) and command.txt in each; a render is
// done when its JSON says every sample completed (a killed one is run again).
#pragma once
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/image_metrics.h"
#include "experiments/compare.h"
#include "illum/framework/render_options.h"

namespace vgi {

struct SweepRender {
  std::string id;                 // stable: a hash of its arguments
  std::string dir;                // DIR/points/<id> or DIR/references/<id>
  std::string stem;               // dir/render.exr or dir/ref.exr
  std::vector<std::string> args;  // `vgi` arguments (render …: renderArgs(options), -o stem)
  RenderOptions options;          // what it renders (args empty: none)
  std::string file;               // a reference given as an existing image (no args)
};

struct SweepPoint {
  SweepRender render;
  std::string scene, method, label;
  nlohmann::json params;  // the grid's values of this point, key → value (text)
  size_t reference = 0;   // index into Experiment::references
  int curve = -1;         // index into Experiment::curves: its counterpart's convergence, or −1
  int spp = 0;            // the method's "spp", or the experiment's
  uint32_t seed = 0;      // this render's seed (with "seeds": the k-th of the point's)
  int full = -1;          // "split": index into Experiment::references of its full reference, or −1
};

// The sweep's comparisons report FLIP (core/flip.h) unless the experiment says "flip": "off".
inline DiffOptions withFlip() {
  DiffOptions d;
  d.flip = FlipMode::Auto;
  return d;
}

struct Experiment {
  std::string name, path, dir;
  std::vector<std::string> scenes;
  int width = 0, height = 0, spp = 0;
  uint32_t seed = 1;
  int seeds = 1;                  // renders per point (seed + kSeedStride·k)
  bool split = false;             // reference.split: each point's full reference too
  std::vector<int> checkpoints;   // sorted, < spp
  std::vector<std::string> aovs;  // besides the image
  DiffOptions diff = withFlip();  // relMSE's ε (absolute); FLIP (the experiment's "flip", auto by default)
  double relativeEpsilon = 0.1;   // the second relMSE's relative ε
  double timeBudgetS = 0;         // > 0: each point's wall-time limit
  struct Animation {
    int frames = 1;  // > 1: the scene's renders are animations of this many frames
    float timeStep = 1.0f, time = 0.0f;
  };
  std::map<std::string, Animation> animation;  // per scene (every scene has its entry)
  bool animated() const;                       // a scene has frames > 1
  std::vector<int> curveCounts;  // the counterparts' convergence checkpoints (sorted; last = its spp)
  ExactDevice exactDevice = ExactDevice::Same;  // where the convergence curves run (reference.device)
  bool exactDeviceGiven = false;  // the file says "device" (then "same" is a demand, not a preference)
  std::vector<SweepRender> references;
  // The counterparts' convergence renders, each against references[curveReference[i]]: one per
  // reference and device (a reference shared by a GL and a CPU method has two).
  std::vector<SweepRender> curves;
  std::vector<size_t> curveReference;
  std::vector<CounterpartChoice> curveChoice;  // per curve: its device, and why not the method's
  std::vector<SweepPoint> points;
};

// Reads and checks the file, expanding the grids into points, before anything
// renders: unknown keys, methods or parameters, empty grids, out-of-range
// values, a reference image of another size, an unwritable DIR are refused
// naming the key and value.
Experiment loadExperiment(const std::string& path, const std::string& dir);

// The shell command of a render (`vgi` = the binary's path), quoted.
std::string sweepCommand(const SweepRender& r, const std::string& vgi);
// Whether a render finished (its JSON has every sample, or its time limit was reached).
bool sweepRenderDone(const SweepRender& r, int spp);
// The --spp of a render's arguments.
int sweepRenderSpp(const SweepRender& r);
// The renders not done yet (references and curves first, then the points), each with the sample
// count that makes it done: what runSweep runs and `vgi sweep --pending` lists.
std::vector<std::pair<const SweepRender*, int>> pendingRenders(const Experiment& e);
// Thrown by runSweep when a render was interrupted (Ctrl-C): the renders that
// finished are kept, and a second run resumes (`vgi sweep` exits 130).
struct SweepInterrupted : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Runs every reference and point not done yet, one process at a time; returns
// how many ran. Prints progress lines to stderr.
int runSweep(const Experiment& e, const std::string& vgi);

// The equal-error time: how long a render whose error-vs-time curve is
// `curve` takes to reach `error` — log-log interpolation between the two
// measurements around it, or, outside the curve, the nearest end's set-up
// plus its per-sample time scaled by Monte Carlo's rate (error ∝ 1/samples,
// for relMSE) and `extrapolated` set.
struct CurvePoint {
  double timeMs, sampleMs, error;
};
struct EqualError {
  bool valid = false, extrapolated = false;
  double timeMs = 0;
};
EqualError equalErrorTime(const std::vector<CurvePoint>& curve, double error);

// An animation render's stem of frame `frame` (the render's own stem for a still).
std::string sweepFrameStem(const SweepRender& r, int frame);

// One row per point and checkpoint, for whatever finished: the point's scene,
// method, label, parameters, spp, time (total, per-sample passes, set-up) and
// per channel relMSE (ε and relative ε), rel. MAE, SSIM and energy against its
// reference, plus GL_RENDERER, machine, git revision. With a convergence
// curve, its rows come first (role "counterpart") and each point row's
// channels carry equal_error_time_ms / _ratio (the counterpart's time to the
// same relMSE with the relative ε, over the point's time; > 1: the method is
// faster) and equal_error_extrapolated.
nlohmann::json collectSweep(const Experiment& e);
// Writes DIR/results.json and DIR/results.csv from collectSweep's rows;
// returns the rows.
nlohmann::json writeSweepResults(const Experiment& e);

}  // namespace vgi
