// `voxelpath`: the voxel path tracer of Thiedemann et al., "Voxel-based
// Global Illumination" (I3D 2011, §5.2): progressive multi-bounce diffuse and
// glossy GI with voxel visibility. Per sample, for every pixel: the direct
// light of the G-buffer point by the deferred pass (shadow maps; area lights
// as one emitter point per sample), then one path (shaders/illum/voxelpath/
// path.comp): BRDF-sampled directions, first hits through the binary grid
// with the chosen GLSL tracer, normal and BRDF at the hit from the
// multi-valued grids (3D textures), the hit's direct light by RSM
// back-projection (diffuse) and evaluated through the light maps (glossy
// lobe), Russian roulette after `rr_depth` bounces. The sample loop
// accumulates the paths (compensated), so --spp N is N paths per pixel.
//
// The exact counterpart is `reference integrator=path` with the same
// `maxdepth` and `rr_depth` (Embree paths, exact shading, NEE + MIS for area
// lights); both split their estimate into `direct` (light reaching x0 along
// one segment: the deferred pass, and the environment seen by x0's bounce
// ray) and `indirect`. The difference is the voxel visibility (conservative
// cells for triangles, the start offset, the passed band), the voxel shading
// (the hit point, the cell's mean normal and BRDF) and the RSM direct light at
// hits (texel resolution, the ε test, shadow-map visibility for the lobe).
// With glossy=false, env=false or clamp > 0 it computes another integral
// than its counterpart (compare reports the difference as error).
//
// Parameters: `vgi render --help-module voxelpath` (and docs/PARAMETERS.md), generated from the
// ParamSet declarations (this file's and its kits'), whose doc strings are the one place they are written.
#include "illum/methods/voxelpath.h"

#include <glad/gl.h>

#include <nlohmann/json.hpp>

#include "core/gpu_scene.h"
#include "core/shader_library.h"
#include "illum/framework/compute_pass.h"
#include "illum/framework/deferred.h"
#include "illum/framework/sample_loop.h"
#include "illum/kits/direct_pass.h"
#include "illum/kits/shared_params.h"
#include "illum/kits/tracer_kit.h"
#include "illum/resources/gpu_scene.h"
#include "illum/resources/light_maps.h"
#include "illum/resources/or_mip_pyramid.h"
#include "illum/resources/value_grids.h"
#include "shaders/illum/voxelpath/params.glsl"
#include "shaders/shared/bindings.glsl"
#include "traverse/gl_ray_tracer.h"
#include "voxelize/value_textures.h"

namespace vgi {

namespace {

class VoxelPathMethod : public Method {
 public:
  VoxelPathMethod(ParamSet& p, const Scene& scene) {
    maxDepth_ = p.getInt("maxdepth", 3,
                         "path vertices with direct light: 1 = direct only, 3 = two interreflections "
                         "(VGI Fig. 14); as reference maxdepth",
                         1, 64);
    rrDepth_ = p.getInt("rr_depth", 3, "bounces before Russian roulette (as reference)", 0, 10000);
    tracer_ = readTracerParam(p);
    offset_ = readOffset(p);
    passThrough_ =
        readPassThrough(p, "the hit voxel's mean normal is the start's (up to sign), or it gives no light");
    hitPoint_ =
        p.getString("hitpoint", "entry",
                    "hit vertex: entry (where the ray enters the voxel), centre (the voxel centre) "
                    "or plane (the ray meets the plane of the voxel's mean normal through its centre)",
                    {"entry", "centre", "plane"});
    backProjection_ = readBackProjection(p);
    glossy_ = p.getBool("glossy", true, "sample and light the Phong lobes (false: diffuse only)");
    clamp_ = p.getFloat("clamp", 0.0f,
                        "firefly clamp: each vertex's contribution clamped to this (max component); 0 = off",
                        0.0f, 1e30f);
    env_ = readEnv(p);
    // Static + frame grid, the pyramid (≈ 4/3 of a grid); the value grids (≈ 3 more) are checked when built.
    grid_ = readBinaryGridParams(p, 4, true);
    readShadowParams(p, shadow_);
    temporal_ = readTemporal(p);
    traceLength_ = 4.0f * scene.bounds().diagonal() + 1e-6f;
  }
  std::vector<std::string> outputs() const override { return {"direct", "indirect"}; }
  SceneNeeds needs() const override {
    SceneNeeds n;
    needGBuffer(n);
    n.add(LightMapNeed{shadow_.resolution, true});
    addVoxelHitNeeds(n, grid_, tracer_, {"normal", "albedo", "glossy"});
    return n;
  }
  void prepareFrame(Frame& f) override {
    ShaderLibrary& shaders = f.shaders();
    voxelDiagonal_ = f.resources.get<GridBox>().voxelDiagonal();
    direct_ = std::make_unique<DirectPass>(shaders, f.resources.get<GpuScene>(), shadow_.bias,
                                           shadow_.normalOffset);
    ShaderDefines defs;
    addTracerDefine(defs, tracer_);
    path_.create(f, {"illum/voxelpath/path.comp.glsl"}, defs,
                 {gpuSceneInput, lightMapsInput, valueTexturesInput, gbufferInput});
    shared::VoxelPathParams& p = path_.params();
    p.maxDepth = maxDepth_;
    p.rrDepth = rrDepth_;
    p.clampMax = clamp_;
    p.env = env_ ? 1 : 0;
    p.shadowBias = shadow_.bias;
    p.normalOffset = shadow_.normalOffset;
    p.seed = f.request.seed;
    p.writeDirect = f.wants("direct") ? 1 : 0;
    p.writeIndirect = f.wants("indirect") ? 1 : 0;
    shared::VoxelHitParams h{};
    h.offset = offset_ * voxelDiagonal_;
    h.voxelDiagonal = voxelDiagonal_;
    h.traceLength = traceLength_;
    h.glossy = glossy_ ? 1 : 0;
    h.backProjection = backProjection_;
    h.passThrough = passThrough_ ? 1 : 0;
    h.hitPoint = hitPointConstant(hitPoint_);
    hits_.set(path_.program(), h);
  }
  bool addSample(Frame& f, int k) override {
    const unsigned sample = f.sampleImage("image");
    {
      auto s = f.profiler.scope("direct");
      direct_->shade(f.gbuffer(), f.resources.get<LightMaps>(), f.camera, sample);
    }
    {
      auto s = f.profiler.scope("paths");
      path_.params().cameraPosition = glm::vec4(f.camera.position, 1.0f);
      path_.params().sampleIndex = uint32_t(k);
      path_.use(f);
      bindTracer(f.resources, f.shaders(), path_.program());
      hits_.bind();
      glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
      bindSampleAndSplitImages(f);
      path_.dispatch(f.width(), f.height());
    }
    return true;
  }
  void finishFrame(Frame& f) override {
    f.extra["voxel_diagonal"] = voxelDiagonal_;
    f.extra["offset_world"] = offset_ * voxelDiagonal_;
    f.extra["clamp"] = clamp_;
    f.extra["clamped"] = clamp_ > 0.0f;
    f.extra["paths_per_sample"] = uint64_t(f.width()) * uint64_t(f.height());
  }

  TemporalSettings temporal() const override { return temporal_; }

 private:
  TemporalSettings temporal_;
  int maxDepth_ = 3, rrDepth_ = 3;
  float offset_ = 0.5f, clamp_ = 0, traceLength_ = 0, voxelDiagonal_ = 0;
  bool passThrough_ = true, glossy_ = true, env_ = true;
  std::string tracer_, hitPoint_;
  int backProjection_ = shared::BACK_PROJECTION_PLANE;
  BinaryGridNeed grid_;
  ShadowParams shadow_;
  std::unique_ptr<DirectPass> direct_;
  ComputePass<shared::VoxelPathParams> path_;
  VoxelHits hits_;
};

}  // namespace

MethodInfo voxelPathMethod() {
  return {"voxelpath",
          "GL voxel path tracing: multi-bounce diffuse + glossy GI through the voxel grid (VGI 5.2)", true,
          [](ParamSet& p, const Scene& s) -> std::unique_ptr<Method> {
            return std::make_unique<VoxelPathMethod>(p, s);
          },
          [](const nlohmann::json& p) {
            return Counterpart{"reference",
                               {"integrator=path", "maxdepth=" + std::to_string(p.at("maxdepth").get<int>()),
                                "rr_depth=" + std::to_string(p.at("rr_depth").get<int>()),
                                "env=" + counterpartText(p.at("env")),
                                p.at("glossy").get<bool>() ? "glossy=all" : "glossy=direct"},
                               {"direct", "indirect"},
                               "",
                               fullPathReference()};
          }};
}

}  // namespace vgi
