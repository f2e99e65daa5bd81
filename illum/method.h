// The interface every rendering method implements, and the explicit registry.
// A method reads its parameters from a ParamSet when it is created (unknown
// keys are errors), then renders frames of a scene into an HDR image.
#pragma once
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/image.h"
#include "core/params.h"
#include "core/profiler.h"
#include "core/scene.h"

namespace vgi {

class GlContext;
class ShaderLibrary;

struct RenderRequest {
  const Scene* scene = nullptr;
  int width = 256, height = 256;
  int spp = 1;
  uint32_t seed = 0;
  int threads = 0;  // CPU threads; 0 = all cores
  float time = 0;   // animation time of this frame
  // An animation calls render() once per frame, in order, on the same Method
  // with `time` = frameTimes[frame]; a method may keep what does not change
  // between its calls (static voxels, programs). A still: one frame.
  std::vector<float> frameTimes;
  int frame = 0;
  GlContext* gl = nullptr;          // set for methods with needsGl()
  ShaderLibrary* shaders = nullptr; // idem
  bool progress = true;             // draw a progress bar on a terminal
  std::vector<std::string> aovs;    // extra outputs asked for (a subset of Method::outputs())
  bool wants(const std::string& aov) const {
    for (auto& a : aovs)
      if (a == aov) return true;
    return false;
  }
};

struct RenderResult {
  Image image;
  int sppCompleted = 0;   // < requested when interrupted (Ctrl-C)
  bool interrupted = false;
  nlohmann::json extra = nlohmann::json::object();  // method-specific stats
  std::map<std::string, Image> aovs;                 // the extra outputs asked for
  std::vector<std::string> built;                    // the resources this render built
  // The timed passes that run once per sample (frame of the spp loop); the
  // others are set-up (voxelization, light maps, uploads). Empty: not split.
  std::vector<std::string> samplePasses;
};

class Method {
 public:
  virtual ~Method() = default;
  virtual RenderResult render(const RenderRequest& request, Profiler& profiler) = 0;
  // Extra output channels (AOVs) it can write besides the combined image.
  virtual std::vector<std::string> outputs() const { return {}; }
};

// The exact computation of the integral an approximate method estimates
// (`vgi compare` renders both): a method, its parameters, and the extra
// outputs both write (compared too).
struct Counterpart {
  std::string method;
  std::vector<std::string> set;   // key=value
  std::vector<std::string> aovs;
};

struct MethodInfo {
  std::string name;
  std::string description;
  bool needsGl;
  // The resources a frame builds (a module builds only these): "gbuffer",
  // "light_maps", "rsm", "binary_grid", "or_mip_pyramid", "bvh", ….
  std::vector<std::string> needs;
  std::function<std::unique_ptr<Method>(ParamSet& params, const Scene& scene)> create;
  // From the method's resolved parameters; empty for a method that is exact itself.
  std::function<Counterpart(const nlohmann::json& params)> counterpart = {};
};

const std::vector<MethodInfo>& methodRegistry();
// Throws naming `option` and listing the known names.
const MethodInfo& findMethod(const std::string& name, const std::string& option = "--method");
std::string defaultMethodName();

}  // namespace vgi
