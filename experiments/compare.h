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

struct Comparison {
  RenderOutput approx, exact;
  Counterpart counterpart;
  CounterpartChoice choice;  // which counterpart, on which device
  int refSpp = 0;
  std::map<std::string, ImageDiff> errors;  // "image" and each AOV the counterpart splits
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
// device: where the counterpart runs (ExactDevice).
Comparison compareWithCounterpart(const RenderOptions& method, int refSpp, const DiffOptions& diff = {},
                                  const std::string& referenceFile = "",
                                  ExactDevice device = ExactDevice::Same);

// Writes stem.<method>.*, stem.exact.* (images, AOVs, stats), the signed
// error images stem.error[.<aov>].exr/.png and stem.json; returns the image
// and stat files (stem.json last).
std::vector<std::string> writeComparison(const Comparison& c, const std::string& stem);

}  // namespace vgi
