// A method against the exact computation of the same integral (its registry
// counterpart, e.g. nearfield → reference integrator=nearfield with the same
// radius and env), rendered with the same scene, size, seed and time: speed
// against error, per output channel. `vgi compare` is this plus printing; a
// sweep or a test calls it directly.
#pragma once
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/image_metrics.h"
#include "illum/framework/method.h"
#include "illum/run/render_job.h"

namespace vgi {

// Where the exact counterpart runs. Speed against error means something only on
// one device (DESIGN.md): by default a GL method's counterpart is the exact
// method's GL twin (reference → reference_gl, MethodInfo::glTwin), a CPU
// method's the CPU one; `Cpu` keeps the registry's (CPU) counterpart.
enum class ExactDevice { Same, Cpu };

struct CounterpartChoice {
  Counterpart counterpart;
  std::string device;       // "gl" or "cpu": where the counterpart runs
  bool sameDevice = false;  // as the method
  std::string note;         // why not on the method's device, when it is not
  nlohmann::json toJson() const;
};

// The counterpart `registry` (the method's registry counterpart) on the device
// asked for. A twin that refuses the parameters (reference_gl: visibility=voxels
// runs on the CPU only) leaves the CPU counterpart, with the reason in `note`.
CounterpartChoice counterpartOnDevice(const RenderOptions& method, const Counterpart& registry,
                                      ExactDevice device);

// The full reference's seed: the counterpart's + 2 (a sweep's convergence curve has + 1), so that
// a model that leaves nothing out shows the two exact renders' noise as its model error, not 0.
constexpr uint32_t kFullReferenceSeedOffset = 2;

// With several seeds (Celarek et al., "Quantifying the Error of Light Transport Algorithms",
// EGSR 2019: one run's error of a Monte Carlo method is one draw of a random variable), run k
// renders the method with seed + kSeedStride·k (never the curve's + 1 or the full reference's + 2)
// against the one counterpart (and full reference), rendered once.
constexpr uint32_t kSeedStride = 3;

// One seed's render of the method: its errors per channel against the model-matched counterpart
// (and, with the split, against the full reference) and its times.
struct SeedRun {
  uint32_t seed = 0;
  std::map<std::string, ImageDiff> errors, totalErrors;
  double msPerFrame = 0, setupMs = 0;
};

// The mean and the sample standard deviation (0 for one value) of one metric over the seeds.
struct SeedStat {
  double mean = 0, sd = 0;
  std::vector<double> values;
};
SeedStat seedStat(const std::vector<double>& values);

// The metrics a seed statistic is kept of, by name (relmse, relmse_trimmed, rel_mae, energy — the
// mean over RGB —, flip — ImageDiff::flipMean —), and their values.
const std::vector<std::string>& seedMetricNames();
double seedMetric(const ImageDiff& d, const std::string& name);

struct Comparison {
  RenderOutput approx, exact;
  Counterpart counterpart;
  CounterpartChoice choice;  // which counterpart, on which device
  int refSpp = 0;
  // The approximation error: the method against its model-matched counterpart, in "image" and
  // each AOV the counterpart splits.
  std::map<std::string, ImageDiff> errors;
  // With the split: the full reference (Counterpart::full, refSpp samples, seed +
  // kFullReferenceSeedOffset) and, per channel, the total error (the method against it) and the
  // model's (the model-matched counterpart against it).
  bool split = false;
  RenderOutput full;
  CounterpartChoice fullChoice;
  uint32_t fullSeed = 0;
  std::map<std::string, ImageDiff> totalErrors, modelErrors;
  // Every seed's run (runs[0] is approx, errors and totalErrors above): `vgi compare --seeds N`.
  std::vector<SeedRun> runs;
  // One metric (seedMetricNames) of one channel over the runs: against the counterpart, or with
  // `total` against the full reference.
  SeedStat overSeeds(const std::string& channel, const std::string& metric, bool total = false) const;
  // Per frame: the passes the method runs per sample (its sample_passes); the
  // rest (voxelization, light maps, uploads) is set-up, paid once per scene
  // or animation frame. A method that does not split counts all per frame.
  double msPerFrame = 0, setupMs = 0;
  int frames = 0;
  bool interrupted = false;        // Ctrl-C stopped a render (what it had is compared)
  bool complete = false;           // false: a render had no full sample; nothing else is set
  nlohmann::json summary() const;  // what stem.json holds (outputs added by writeComparison)
};

// Renders `method` (its options as given) and its counterpart with refSpp
// samples. Throws if the method has no counterpart or refSpp is out of range.
// referenceFile: an existing image of the counterpart (its AOVs beside it as
// <stem>.<aov>.exr, its stats as <stem>.json when present) instead of
// rendering it; refused if its size differs.
// device: where the counterpart runs (ExactDevice). split: also render the full reference
// (on the same device as the counterpart) and split each error into model and approximation.
// seeds: the method's runs (≥ 1; the counterpart renders once).
Comparison compareWithCounterpart(const RenderOptions& method, int refSpp, const DiffOptions& diff = {},
                                  const std::string& referenceFile = "",
                                  ExactDevice device = ExactDevice::Same, bool split = false, int seeds = 1);

// Writes stem.<method>.*, stem.exact.* (images, AOVs, stats), with the split stem.full.*, the
// signed error images stem.error[.<aov>].exr/.png (the approximation's) and stem.json; returns the
// image and stat files (stem.json last).
std::vector<std::string> writeComparison(const Comparison& c, const std::string& stem);

}  // namespace vgi
