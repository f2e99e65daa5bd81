// `nearfield`: real-time near-field single-bounce indirect light with voxel
// visibility and RSM back-projection — Thiedemann, Henrich, Grosch, Müller,
// "Voxel-based Global Illumination", I3D 2011, §5.1 (Fig. 7, 12, 15).
//
// Needs (built and kept across an animation's frames by the framework's
// SceneResources, illum/framework/resources.h): a binary grid (any voxelizer of
// voxelize/, the atlas voxelizer by default) with its OR-mip pyramid on the
// GPU, reflective shadow maps of every light, the G-buffer. Per sample
// (`--spp` jittered passes of the framework's sample loop, directions
// rotated): G-buffer (the loop's) → deferred direct light →
// indirect gathering at 1, ½ or ¼ resolution (shaders/illum/nearfield/
// indirect.comp: N cosine rays per pixel, interleaved k×k, first hit by the
// chosen GLSL tracer, back-projection into the RSMs, environment beyond r)
// → geometry-aware blur → joint bilateral upsampling and composite
// direct + albedo × indirect.
//
// Back-projection: VGI tests the voxel entry point against the RSM with
// ε ≥ a voxel diagonal (`backprojection=entry`). By default the texel the
// entry projects to names the surface the light sees there, the ray is
// intersected with that surface's plane, and that point is tested with the
// texel term of ε only (`plane`): the voxel entry lies up to a diagonal off
// the surface, which let the ε test take light from neighbouring surfaces and
// drop lit ones at grazing angles (indirect rel. MAE on the Cornell box at
// 256³, full resolution: 0.22 → 0.09; docs/BENCHMARKS.md). A hit voxel whose
// entry point a light sees past holds no surface there, and the ray goes on
// (`passthrough`).
//
// The exact counterpart is `reference --set integrator=nearfield` with the
// same `radius` and `env`: it differs by voxel visibility (and the start
// offset), RSM back-projection (texel resolution, ε, diffuse-only radiance,
// no emission at the hit point), shadow-mapped direct light, and the reduced
// resolution with its blur and upsampling.
//
// Parameters: `vgi render --help-module nearfield` (and docs/PARAMETERS.md), generated from the
// ParamSet declarations (this file's and its kits'), whose doc strings are the one place they are written.
#include "illum/methods/nearfield.h"

#include <glad/gl.h>

#include <cmath>
#include <glm/gtc/type_ptr.hpp>

#include "core/error.h"
#include "core/gpu_scene.h"
#include "core/shader_library.h"
#include "illum/framework/deferred.h"
#include "illum/framework/sample_loop.h"
#include "illum/kits/direct_pass.h"
#include "illum/kits/gather_kit.h"
#include "illum/kits/shared_params.h"
#include "illum/kits/tracer_kit.h"
#include "illum/resources/gpu_scene.h"
#include "illum/resources/light_maps.h"
#include "illum/resources/or_mip_pyramid.h"
#include "shaders/illum/nearfield/params.glsl"
#include "shaders/shared/bindings.glsl"
#include "traverse/gl_ray_tracer.h"
#include "voxelize/voxelizer.h"

namespace vgi {

namespace {

struct NearFieldParams {
  GatherSettings gather;
  float radius = 0, offset = 0.5f;
  bool env = true, passThrough = true;
  std::string tracer = "hierarchical";
  int backProjection = shared::BACK_PROJECTION_PLANE;
  BinaryGridNeed grid;
  ShadowParams shadow;
};

class NearFieldMethod : public Method {
 public:
  NearFieldMethod(ParamSet& p, const Scene& scene) {
    NearFieldParams& q = p_;
    q.gather = readGatherParams(p, "indirect", true);
    readGatherWallParams(p, q.gather, true, true);
    // The default makes near-field GI plainly visible: 0.5 × the diagonal
    // gathers 82 % of the exact one-bounce light on the Cornell box (0.1 ×:
    // 8 %) and all of it on Sibenik (docs/BENCHMARKS.md, the radius table).
    q.radius = p.getFloat("radius", kDefaultNearFieldRadius * scene.bounds().diagonal(),
                          "ray length r in world units (default 0.5 x scene diagonal)", 1e-30f, 1e30f);
    q.tracer = readTracerParam(p);
    q.env = readEnv(p);  // rays that leave the radius: directional occlusion
    q.backProjection = readBackProjection(p);
    // VGI's entry test takes light from any surface within ε ≥ a voxel diagonal, the receiver's own
    // voxels included, so with `entry` the rays start VGI's full diagonal off.
    const bool entry = q.backProjection == shared::BACK_PROJECTION_ENTRY;
    q.offset = readOffset(p, entry ? 1.0f : kDefaultOffset,
                          "1 with backprojection=entry: its test takes light from the receiver's own voxels "
                          "unless the rays start a full diagonal off, as VGI's do");
    q.passThrough = readPassThrough(p,
                                    "a light sees through the hit voxel's entry point (empty there), or the "
                                    "voxel gives no light");

    q.grid = readBinaryGridParams(p, 4);  // static + frame grid (atlas), the pyramid (≈ 4/3 of a grid)
    readShadowParams(p, q.shadow);
    temporal_ = readTemporal(p);
  }
  std::vector<std::string> outputs() const override { return {"direct", "indirect"}; }
  SceneNeeds needs() const override {
    SceneNeeds n;
    needGBuffer(n);
    n.add(LightMapNeed{p_.shadow.resolution, true});
    addTracerNeeds(n, p_.grid, p_.tracer);
    return n;
  }
  void prepareFrame(Frame& f) override;
  bool addSample(Frame& f, int k) override;
  void finishFrame(Frame& f) override;

  TemporalSettings temporal() const override { return temporal_; }

 private:
  TemporalSettings temporal_;
  NearFieldParams p_;
  // Per frame (prepareFrame).
  GatherKit kit_;
  std::unique_ptr<DirectPass> direct_;
  ComputePass<shared::NearFieldPassParams> indirect_;
  ComputePass<shared::NearFieldPassParams> indirectFixup_;  // gather.fixup: the same, at listed pixels
  float voxelDiagonal_ = 0;
};

void NearFieldMethod::prepareFrame(Frame& f) {
  ShaderLibrary& shaders = f.shaders();
  voxelDiagonal_ = f.resources.get<GridBox>().voxelDiagonal();
  ShaderDefines tracerDefs;
  addTracerDefine(tracerDefs, p_.tracer);
  // The neighbours' visibility tests start at least a voxel diagonal off their surfaces (half a
  // diagonal leaves a surface lying on a cell boundary inside its own second layer of voxels).
  kit_.prepare(f, p_.gather, tracerDefs, std::max(p_.offset, 1.0f) * voxelDiagonal_);
  direct_ = std::make_unique<DirectPass>(shaders, f.resources.get<GpuScene>(), p_.shadow.bias,
                                         p_.shadow.normalOffset);
  ShaderDefines defs;
  addTracerDefine(defs, p_.tracer);
  indirect_.create(f, {"illum/nearfield/indirect.comp.glsl"}, defs,
                   {gpuSceneInput, lightMapsInput, gbufferInput});
  // What stays the same over the frame's samples.
  GatherKit::checkPass(indirect_);
  if (p_.gather.fixup) {
    ShaderDefines fixupDefs = defs;
    fixupDefs["GATHER_FIXUP"] = "1";
    indirectFixup_.create(f, {"illum/nearfield/indirect.comp.glsl"}, fixupDefs,
                          {gpuSceneInput, lightMapsInput, gbufferInput});
  }
  shared::NearFieldPassParams& ip = indirect_.params();
  ip.radius = p_.radius;
  ip.offset = p_.offset * voxelDiagonal_;
  ip.voxelDiagonal = voxelDiagonal_;
  ip.env = p_.env ? 1 : 0;
  ip.backProjection = p_.backProjection;
  ip.passThrough = p_.passThrough ? 1 : 0;
}

bool NearFieldMethod::addSample(Frame& f, int k) {
  {
    auto s = f.profiler.scope("direct");
    direct_->shade(f.gbuffer(), f.resources.get<LightMaps>(), f.camera, f.sampleImage("image"));
  }
  {
    auto s = f.profiler.scope("indirect");
    indirect_.use(f);
    bindTracer(f.resources, f.shaders(), indirect_.program());
    kit_.setSample(k, f.request.seed);
    kit_.dispatchGather(kit_.settings().rays, GatherKit::kRaysPerDispatch);
  }
  const auto tracer = [&](unsigned program) { bindTracer(f.resources, f.shaders(), program); };
  kit_.resolve(f, tracer, [&] {
    indirectFixup_.params() = indirect_.params();
    indirectFixup_.use(f);
    tracer(indirectFixup_.program());
    kit_.dispatchFixup(kit_.settings().rays, GatherKit::kRaysPerDispatch);
  });
  return true;
}

void NearFieldMethod::finishFrame(Frame& f) {
  nlohmann::json& extra = f.extra;
  extra["radius"] = p_.radius;
  extra["voxel_diagonal"] = voxelDiagonal_;
  extra["offset_world"] = p_.offset * voxelDiagonal_;
  extra["indirect_size"] = {kit_.width(), kit_.height()};
  extra["blur_window_px"] = kit_.blurWindow();
  extra["rays_per_frame"] = uint64_t(kit_.width()) * kit_.height() * p_.gather.rays;
  kit_.stats(f);
}

}  // namespace

MethodInfo nearFieldMethod() {
  return {"nearfield", "GL near-field one-bounce GI: voxel visibility + RSM back-projection (VGI 5.1)", true,
          [](ParamSet& p, const Scene& s) -> std::unique_ptr<Method> {
            return std::make_unique<NearFieldMethod>(p, s);
          },
          [](const nlohmann::json& p) {
            return Counterpart{"reference",
                               {"integrator=nearfield", "radius=" + counterpartText(p.at("radius")),
                                "env=" + counterpartText(p.at("env")), "glossy=direct"},
                               {"direct", "indirect"},
                               "the model: one bounce from within the radius, reflected diffusely "
                               "(glossy=direct)",
                               fullPathReference("indirect")};
          }};
}

}  // namespace vgi
