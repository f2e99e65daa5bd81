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
// Parameters
// | key           | type  | default | meaning                                            |
// |---------------|-------|---------|----------------------------------------------------|
// | shadow_res    | int   | 1024    | shadow map size (per face)                         |
// | shadow_bias   | float | 1.0     | depth bias in shadow-map texels, at the texel      |
// |               |       |         | centre on the receiver's plane (shared/light_maps) |
// | normal_offset | float | 0       | lookup offset along the normal, in texels          |
#include "illum/direct.h"

#include "core/error.h"
#include "core/gpu_scene.h"
#include "illum/deferred.h"
#include "illum/light_maps.h"
#include "illum/sample_loop.h"

namespace vgi {

void readShadowParams(ParamSet& p, ShadowParams& s) {
  s.resolution = p.getInt("shadow_res", 1024, "shadow map size (per face)", 16, 8192);
  s.bias = p.getFloat("shadow_bias", 1.0f,
                      "depth bias in shadow-map texels (receiver plane at the texel centre; slope-scaled "
                      "within 0.6 deg of grazing)",
                      0.0f, 100.0f);
  s.normalOffset =
      p.getFloat("normal_offset", 0.0f, "lookup offset along the normal, in texels", 0.0f, 100.0f);
}

namespace {

class DirectMethod : public Method {
 public:
  DirectMethod(ParamSet& p, const Scene&) { readShadowParams(p, shadow_); }
  SceneNeeds needs() const override {
    SceneNeeds n;
    n.gbuffer = true;
    n.lightMaps = LightMapNeed{shadow_.resolution, false};
    return n;
  }
  void prepareFrame(Frame& f) override {
    pass_ =
        std::make_unique<DirectPass>(f.shaders(), f.resources.gpuScene(), shadow_.bias, shadow_.normalOffset);
  }
  bool addSample(Frame& f, int) override {
    auto s = f.profiler.scope("shade");
    pass_->shade(f.gbuffer(), f.resources.lightMaps(), f.camera, f.sampleImage("image"));
    return true;
  }

 private:
  ShadowParams shadow_;
  std::unique_ptr<DirectPass> pass_;
};

}  // namespace

std::unique_ptr<Method> createDirectMethod(ParamSet& params, const Scene& scene) {
  return std::make_unique<DirectMethod>(params, scene);
}

}  // namespace vgi
