// The parameters of the exact integrators, read and documented once for the
// two implementations of the same estimators: `reference` (CPU, Embree) and
// `reference_gl` (GL, the GPU BVH). Both take the same keys with the same
// defaults, so a counterpart's `set` runs unchanged on either device.
#pragma once
#include <glm/glm.hpp>

namespace vgi {

class ParamSet;
struct Scene;

enum class ExactIntegrator { Path, Direct, NearField, Ao };
enum class EmitterSampling { Mis, Light, Brdf };
// The surfaces that reflect by their Phong lobe (a model-matched counterpart's omission,
// DESIGN.md "Exact counterparts"): All; First — the visible surface only, every bounce surface
// diffuse (the cone methods' model); Direct — only the visible surface's direct light, the
// indirect light it reflects and every bounce surface diffuse (the diffuse-bounce methods').
// The values are shared with the GL twin (shaders/illum/reference_gl/params.glsl, GLOSSY_*).
enum class GlossyModel { All = 0, First = 1, Direct = 2 };

struct ExactParams {
  ExactIntegrator integrator = ExactIntegrator::Path;
  const char* integratorName = "path";
  int maxDepth = 8, rrDepth = 3;  // direct: maxDepth 1
  float radius = 0;               // nearfield / ao, world units
  bool env = true;                // path/direct/nearfield: the environment lights the scene
  bool envIndirect = false;       // path: the environment seen from the first surface counts as indirect
  bool voxelVisibility = false;   // nearfield / path: bounce rays' first hits through voxels
  glm::uvec3 voxels{128};
  float offset = 1.0f;
  EmitterSampling emitterSampling = EmitterSampling::Mis;
  GlossyModel glossy = GlossyModel::All;  // path / nearfield
  // The integrators that split their estimate into "direct" and "indirect" outputs.
  bool splitsDirectIndirect() const {
    return integrator == ExactIntegrator::NearField || integrator == ExactIntegrator::Path;
  }
};

// Reads and documents integrator, maxdepth, rr_depth, radius, env, env_channel, glossy, visibility,
// voxels, offset and emitter_sampling; only the integrator's own are read (a
// key of another integrator is an error naming both). `method`: the module
// name in messages; `voxelsSupported`: whether visibility=voxels is offered
// (it runs on the CPU only).
ExactParams readExactParams(ParamSet& params, const Scene& scene, const char* method, bool voxelsSupported);

}  // namespace vgi
