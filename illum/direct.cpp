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
#include "core/progress.h"
#include "illum/deferred.h"
#include "illum/light_maps.h"

namespace vgi {

void readShadowParams(ParamSet& p, ShadowParams& s) {
  s.resolution = p.getInt("shadow_res", 1024, "shadow map size (per face)", 16, 8192);
  s.bias = p.getFloat("shadow_bias", 1.0f, "depth bias in shadow-map texels (receiver plane at the texel centre; slope-scaled within 0.6 deg of grazing)", 0.0f, 100.0f);
  s.normalOffset = p.getFloat("normal_offset", 0.0f, "lookup offset along the normal, in texels", 0.0f, 100.0f);
}

namespace {

class DirectMethod : public Method {
 public:
  DirectMethod(ParamSet& p, const Scene&) { readShadowParams(p, shadow_); }
  RenderResult render(const RenderRequest& req, Profiler& profiler) override;

 private:
  ShadowParams shadow_;
};

RenderResult DirectMethod::render(const RenderRequest& req, Profiler& prof) {
  VGI_CHECK(req.gl && req.shaders);
  const Scene& scene = *req.scene;
  std::unique_ptr<GpuScene> gpu;
  {
    auto s = prof.scope("upload");
    gpu = std::make_unique<GpuScene>(scene, req.time);
  }
  GBuffer gbuffer(req.width, req.height, *req.shaders);
  Accumulator accum(req.width, req.height);
  LightMaps maps(scene, *gpu, *req.shaders, shadow_.resolution, false, prof);
  DirectPass direct(*req.shaders, *gpu, shadow_.bias, shadow_.normalOffset);

  RenderResult result;
  ProgressBar bar("direct", req.spp);
  int done = 0;
  for (; done < req.spp && !interruptRequested(); ++done) {
    FrameCamera cam = frameCamera(scene.camera, gpu->bounds(), req.width, req.height, done, req.spp);
    {
      auto s = prof.scope("gbuffer");
      gbuffer.render(*gpu, cam);
    }
    {
      auto s = prof.scope("shade");
      direct.shade(gbuffer, maps, cam, accum);
    }
    prof.resolve(false);
    if (req.progress) bar.advance();
  }
  bar.finish();
  {
    auto s = prof.scope("readback");
    result.image = accum.read();
  }
  result.samplePasses = {"gbuffer", "shade"};
  result.sppCompleted = done;
  result.interrupted = done < req.spp;
  result.extra["light_maps"] = maps.describe();
  result.built = {"gbuffer", "light_maps"};
  return result;
}

}  // namespace

std::unique_ptr<Method> createDirectMethod(ParamSet& params, const Scene& scene) {
  return std::make_unique<DirectMethod>(params, scene);
}

}  // namespace vgi
