// `direct`: deferred direct lighting on the GPU — the first GL module and the
// base the GI modules add to. G-buffer (position, normal, albedo), one distance
// map per light (illum/light_maps: cube faces for point lights and wide spot
// lights, one face for narrow spots, an orthographic map fitted to the scene
// for directional lights), then a compute pass that evaluates every delta
// light with the shared kernels (shaders/shared/lights, brdf) — the same code
// the Embree reference (`reference --set integrator=direct`) runs, so their
// difference is the shadow-map error. The shadow test compares, at the
// centre of the map's texel, the stored distance with the receiver's plane
// (its geometric normal is in the G-buffer), so planes do not shadow
// themselves at grazing light and the bias stays small. `--spp N` accumulates N frames with
// sub-pixel jitter (Halton 2,3) so edges converge to the same box-filtered
// pixel as the reference.
//
// Parameters: `vgi render --help-module direct` (and docs/PARAMETERS.md), generated from the
// ParamSet declarations (this file's and its kits'), whose doc strings are the one place they are written.
#include "illum/methods/direct.h"

#include "core/error.h"
#include "core/gpu_scene.h"
#include "illum/framework/deferred.h"
#include "illum/framework/sample_loop.h"
#include "illum/kits/direct_pass.h"
#include "illum/kits/shared_params.h"
#include "illum/resources/gpu_scene.h"
#include "illum/resources/light_maps.h"

namespace vgi {

namespace {

class DirectMethod : public Method {
 public:
  DirectMethod(ParamSet& p, const Scene&) { readShadowParams(p, shadow_); }
  SceneNeeds needs() const override {
    SceneNeeds n;
    needGBuffer(n);
    n.add(LightMapNeed{shadow_.resolution, false});
    return n;
  }
  void prepareFrame(Frame& f) override {
    pass_ = std::make_unique<DirectPass>(f.shaders(), f.resources.get<GpuScene>(), shadow_.bias,
                                         shadow_.normalOffset);
  }
  bool addSample(Frame& f, int) override {
    auto s = f.profiler.scope("shade");
    pass_->shade(f.gbuffer(), f.resources.get<LightMaps>(), f.camera, f.sampleImage("image"));
    return true;
  }

 private:
  ShadowParams shadow_;
  std::unique_ptr<DirectPass> pass_;
};

}  // namespace

MethodInfo directMethod() {
  return {"direct", "GL deferred direct lighting with shadow maps (delta lights, emission)", true,
          [](ParamSet& p, const Scene& s) -> std::unique_ptr<Method> {
            return std::make_unique<DirectMethod>(p, s);
          },
          [](const nlohmann::json&) {
            return Counterpart{
                "reference",
                {"integrator=direct", "env=false"},
                {},
                "neither side integrates the environment light (shadow maps cannot see the sky); "
                "the environment is the background only",
                fullPathReference()};
          }};
}

}  // namespace vgi
