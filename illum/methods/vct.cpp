// `vct`: voxel cone tracing — Crassin et al., "Interactive Indirect
// Illumination Using Voxel Cone Tracing" (2011), as the VCT thesis (Dinse
// 2015, ../shared/papers/000_…) implements it with a dense volume:
//   1. §3.1 voxelization: every (triangle, cell) pair of the three-axis
//      conservative rasterization is lit with the shadow-mapped diffuse direct
//      light and averaged into the cell (illum/cone_kit: radiance=inject), or
//      the atlas voxelizer's radiance channel is used (radiance=atlas); the
//      opacity is the binary grid of `voxelizer` (default hybrid: the
//      thesis' conservative voxelization — the triangle–box cells close thin
//      walls — with the small triangles set triangle-parallel in the geometry
//      shader, as Basgier 2015 §3.4–3.5 builds it: the same cells to float
//      rounding, a tenth of the time).
//      Stored dense (3D textures) or, volume=svo, as the papers' sparse voxel
//      octree (illum/resources/sparse_octree.h: the same values at the same
//      resolution, read through the same coneSample).
//   2. §3.2 pre-integration: a six-direction anisotropic chain (front-to-back
//      composition of 2×2×2 blocks along each axis direction) or isotropic
//      2×2×2 means (voxelize/value_textures, the value grids' own builder).
//   3. §3.3 cone tracing (shaders/illum/vct/cones.glsl): diffuse cones at the
//      gather kit's resolution (default ½, joint bilateral upsampling, §3.4),
//      their weights the cosine-weighted share of the hemisphere nearest each
//      axis (Σ = π); a specular cone along the reflected view direction
//      (aperture from the Phong exponent); AO from the diffuse cones' opacity
//      with the falloff λ; soft shadows by a cone toward each light.
// Deviations, stated: the opacity correction for the step length (Crassin et
// al. §4.2; the thesis' Algorithm 1 has none, which makes the result depend on
// the step); cubic cells; a receiver guard on the mip level (cones.glsl);
// level-0 radiance seen from the cone's side (`directional`, ours; level0 by
// default, docs/BENCHMARKS.md "Leaks: vct"); the gather kit's wall remedies
// and a level cap as parameters for leak studies (off by default); the
// constellation turns per interleave set and per sample, so `vgi render --spp
// N` converges over azimuths. The faces are mixed by |d| as the thesis does
// (`face_weights=squared`: by d², measured worse).
//
// Outputs: indirect (diffuse + specular), direct, ao, specular. The image is
// direct + indirect (AO is an output only: the counterpart's integral has none).
// Counterpart: reference integrator=path maxdepth=2 (one indirect bounce).
//
// Parameters: `vgi render --help-module vct` (and docs/PARAMETERS.md), generated from the
// ParamSet declarations (this file's and its kits'), whose doc strings are the one place they are written.
#include "illum/methods/vct.h"

#include <glad/gl.h>

#include <cmath>

#include "core/error.h"
#include "core/gpu_scene.h"
#include "core/shader_library.h"
#include "illum/framework/compute_pass.h"
#include "illum/framework/deferred.h"
#include "illum/framework/sample_loop.h"
#include "illum/kits/cone_kit.h"
#include "illum/kits/direct_pass.h"
#include "illum/kits/gather_kit.h"
#include "illum/kits/shared_params.h"
#include "illum/kits/tracer_kit.h"
#include "illum/resources/gpu_scene.h"
#include "illum/resources/light_maps.h"
#include "shaders/illum/vct/params.glsl"
#include "shaders/shared/bindings.glsl"
#include "traverse/gl_ray_tracer.h"

namespace vgi {

namespace {

class VctMethod : public Method {
 public:
  VctMethod(ParamSet& p, const Scene& scene) {
    const float diag = scene.bounds().diagonal();
    vol_ = readConeVolumeParams(p, true, true, true, 1.0f);
    cones_ = p.getInt("diffuse_cones", 6,
                      "diffuse cones: 1 (the normal) or n (the normal + n-1 on a ring at 63.4 deg; 6: "
                      "icosahedron vertices)",
                      1, 16);
    aperture_ = p.getFloat("aperture", 60.0f, "diffuse cones' full opening angle, degrees", 1.0f, 179.0f);
    maxDistance_ = p.getFloat("max_distance", diag, "cone length in world units (default the scene diagonal)",
                              1e-30f, 1e30f);
    guard_ = p.getBool("plane_guard", true,
                       "cap a cone sample's mip level so it cannot reach the receiver's tangent plane (ours; "
                       "false: the thesis' cones)");
    offset_ =
        readOffset(p, 1.0f,
                   "1 for cones: an apex a diagonal off lies outside the voxel of the receiver's point, "
                   "which a cone's first sample would read");
    diffuse_ = p.getBool("diffuse", true,
                         "diffuse indirect light from the diffuse cones (false: they give the AO only)");
    specular_ = p.getBool("specular", true, "specular cone along the reflected view direction (ks > 0)");
    skipEmpty_ = p.getBool("skip_empty", true, "empty-space skipping of the specular cone");
    ao_ = p.getBool("ao", true, "the ao output (the diffuse cones' opacity)");
    aoRadius_ = p.getFloat(
        "ao_radius", kDefaultAoRadius * diag,
        "AO radius, world units (default 0.1 x scene diagonal, as reference integrator=ao)", 1e-30f, 1e30f);
    falloff_ =
        p.getFloat("falloff", 0.0f, "AO distance falloff lambda of 1/(1 + lambda t / ao_radius)", 0.0f, 1e6f);
    shadows_ =
        p.getBool("shadows", false, "cone-traced soft shadows of the delta lights instead of shadow maps");
    shadowAperture_ =
        p.getFloat("shadow_aperture", 3.0f, "shadow cones' full opening angle, degrees", 0.0f, 90.0f);
    shadowStop_ = p.getFloat(
        "shadow_stop", 4.0f,
        "shadow cones end this many cone widths (at least voxel diagonals) before the light", 0.0f, 100.0f);
    env_ = readEnv(p);
    gather_ = readGatherParams(p, "diffuse cone", true, false, 2);
    // The kit's wall remedies (nearfield's): the edge mask traces the cone volume's grid
    // (hierarchical, through its pyramid); the fix-up traces the cones again at full rate.
    readGatherWallParams(p, gather_, false, false);
    temporal_ = readTemporal(p);
    constellation_ = ringConstellation(true, cones_ - 1, glm::degrees(std::atan(2.0f)));
  }
  std::vector<std::string> outputs() const override {
    if (ao_) return {"direct", "indirect", "ao", "specular"};
    return {"direct", "indirect", "specular"};
  }
  SceneNeeds needs() const override {
    SceneNeeds n;
    needGBuffer(n);
    // The direct light (radiance=texels: the same maps, reflective, inject the volume too).
    n.add(LightMapNeed{vol_.shadow.resolution, vol_.radiance == ConeRadiance::Texels});
    vol_.addNeed(n);
    if (gather_.visibility) addTracerNeeds(n, vol_.need().grid, kWallTracer);
    return n;
  }
  void prepareFrame(Frame& f) override {
    ShaderLibrary& shaders = f.shaders();
    const float diag = f.resources.get<GridBox>().voxelDiagonal();
    ShaderDefines tracerDefs;
    addTracerDefine(tracerDefs, kWallTracer);
    kit_.prepare(f, gather_, tracerDefs, std::max(offset_, 1.0f) * diag);
    direct_ = std::make_unique<DirectPass>(shaders, f.resources.get<GpuScene>(), vol_.shadow.bias,
                                           vol_.shadow.normalOffset);
    ShaderDefines defs;
    vol_.addDefines(defs);
    diffusePass_.create(f, {"illum/vct/diffuse.comp.glsl"}, defs, {gpuSceneInput, gbufferInput});
    shade_.create(f, {"illum/vct/shade.comp.glsl"}, defs, {gpuSceneInput, lightMapsInput, gbufferInput});
    if (gather_.fixup) {
      ShaderDefines fixupDefs = defs;
      fixupDefs["GATHER_FIXUP"] = "1";
      diffuseFixup_.create(f, {"illum/vct/diffuse.comp.glsl"}, fixupDefs, {gpuSceneInput, gbufferInput});
    }
    GatherKit::checkPass(diffusePass_);
    shared::VctDiffuseParams& d = diffusePass_.params();
    VGI_CHECK(constellation_.size() <= std::size(d.cones));
    std::copy(constellation_.begin(), constellation_.end(), d.cones);
    d.tanHalf = std::tan(glm::radians(aperture_) * 0.5f);
    d.maxDistance = maxDistance_;
    d.offset = offset_ * diag;
    d.aoRadius = aoRadius_;
    d.falloff = falloff_;
    d.env = env_ ? 1 : 0;
    d.diffuse = diffuse_ ? 1.0f : 0.0f;
    d.guard = guard_ ? 1 : 0;
    const int ring = std::max(1, cones_ - 1);
    d.sets = gather_.interleave;
    d.setTurn = 2.0f * float(M_PI) / float(ring) / float(gather_.interleave * gather_.interleave);
    shared::VctShadeParams& s = shade_.params();
    s.guard = guard_ ? 1 : 0;
    s.specular = specular_ ? 1 : 0;
    s.shadows = shadows_ ? 1 : 0;
    s.skipEmpty = skipEmpty_ ? 1 : 0;
    s.env = env_ ? 1 : 0;
    s.shadowBias = vol_.shadow.bias;
    s.normalOffset = vol_.shadow.normalOffset;
    s.shadowTanHalf = std::tan(glm::radians(shadowAperture_) * 0.5f);
    s.offset = offset_ * diag;
    s.maxDistance = maxDistance_;
    s.voxelDiagonal = diag;
    s.shadowStop = shadowStop_;
    s.writeIndirect = f.wants("indirect") ? 1 : 0;
    s.writeDirect = f.wants("direct") ? 1 : 0;
    s.writeAo = f.wants("ao") ? 1 : 0;
    s.writeSpecular = f.wants("specular") ? 1 : 0;
    aoLow_ = f.scratchTexture("vct_ao", kit_.width(), kit_.height(), GL_RGBA32F);
    aoFull_ = f.scratchTexture("vct_ao_full", f.width(), f.height(), GL_RGBA32F);
  }
  bool addSample(Frame& f, int k) override {
    ShaderLibrary& shaders = f.shaders();
    const ConeSource& volume = f.resources.get<ConeSource>();
    {
      auto s = f.profiler.scope("direct");
      direct_->shade(f.gbuffer(), f.resources.get<LightMaps>(), f.camera, f.sampleImage("image"));
    }
    const int ring = std::max(1, cones_ - 1);
    // The ring turns per sample (Halton 3), the whole sequence shifted by the seed (gather_kit.h).
    const float turn = 2.0f * float(M_PI) / float(ring) *
                       glm::fract((k == 0 ? 0.0f : halton(k, 3)) + seedShift(f.request.seed).x);
    {
      auto s = f.profiler.scope("diffuse_cones");
      diffusePass_.params().turn = turn;
      diffusePass_.use(f);
      volume.bind(shaders, diffusePass_.program(), vol_.step);
      glBindImageTexture(IMAGE_OUTPUT2, aoLow_, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
      kit_.dispatchGather(cones_, kConesPerDispatch);
    }
    const auto tracer = [&](unsigned program) { bindTracer(f.resources, shaders, program); };
    kit_.resolve(f, tracer, [&] {
      diffuseFixup_.params() = diffusePass_.params();
      diffuseFixup_.use(f);
      volume.bind(shaders, diffuseFixup_.program(), vol_.step);
      kit_.dispatchFixup(cones_, kConesPerDispatch);
    });
    if (ao_ && f.wants("ao")) kit_.resolveValue(f, aoLow_, aoFull_, "ao", tracer);
    {
      auto s = f.profiler.scope("cones_full");
      shade_.params().cameraPosition = glm::vec4(f.camera.position, 1.0f);
      shade_.use(f);
      volume.bind(shaders, shade_.program(), vol_.step);
      glBindTextureUnit(TEXUNIT_PASS_INPUT, aoFull_);
      bindSampleAndSplitImages(f);
      const char* extra[2] = {"ao", "specular"};
      const unsigned units[2] = {IMAGE_SAMPLE_AOV2, IMAGE_SAMPLE_AOV3};
      for (int i = 0; i < 2; ++i)
        glBindImageTexture(units[i], f.sampleImage(f.wants(extra[i]) ? extra[i] : "image"), 0, GL_FALSE, 0,
                           GL_READ_WRITE, GL_RGBA32F);
      shade_.dispatch(f.width(), f.height());
    }
    return true;
  }
  void finishFrame(Frame& f) override {
    f.extra["voxel_size"] = f.resources.get<ConeSource>().voxelSize();
    f.extra["offset_world"] = offset_ * f.resources.get<GridBox>().voxelDiagonal();
    f.extra["max_distance"] = maxDistance_;
    f.extra["ao_radius"] = aoRadius_;
    f.extra["diffuse_size"] = {kit_.width(), kit_.height()};
    nlohmann::json cones = nlohmann::json::array();
    for (auto& c : constellation_) cones.push_back({c.x, c.y, c.z, c.w});
    f.extra["diffuse_constellation"] = cones;  // tangent-space axes, w the cosine share
    kit_.stats(f);
  }

  TemporalSettings temporal() const override { return temporal_; }

 private:
  TemporalSettings temporal_;
  static constexpr int kConesPerDispatch = 16;
  static constexpr const char* kWallTracer = "hierarchical";  // blur_visibility's traces
  ConeVolumeSettings vol_;
  int cones_ = 6;
  float aperture_ = 60, maxDistance_ = 1, offset_ = 1, aoRadius_ = 1, falloff_ = 0, shadowAperture_ = 3,
        shadowStop_ = 4;
  bool guard_ = true, diffuse_ = true, specular_ = true, skipEmpty_ = true, ao_ = true, shadows_ = false,
       env_ = true;
  GatherSettings gather_;
  std::vector<glm::vec4> constellation_;
  GatherKit kit_;
  std::unique_ptr<DirectPass> direct_;
  ComputePass<shared::VctDiffuseParams> diffusePass_;
  ComputePass<shared::VctDiffuseParams> diffuseFixup_;  // gather.fixup: the same, at listed pixels
  ComputePass<shared::VctShadeParams> shade_;
  unsigned aoLow_ = 0, aoFull_ = 0;
};

}  // namespace

MethodInfo vctMethod() {
  return {
      "vct",
      "GL voxel cone tracing: injected radiance, anisotropic pre-integration, diffuse + specular cones, AO, "
      "soft shadows (Crassin et al. 2011; Dinse 2015)",
      true,
      [](ParamSet& p, const Scene& s) -> std::unique_ptr<Method> {
        return std::make_unique<VctMethod>(p, s);
      },
      [](const nlohmann::json& p) {
        return Counterpart{
            "reference",
            {"integrator=path", "maxdepth=2", "env=" + counterpartText(p.at("env")), "env_channel=indirect",
             "glossy=first"},
            {"direct", "indirect"},
            "the environment seen through the cones is indirect on both sides (as nearfield counts "
            "it); the model: one bounce, glossy at the visible surface only (the voxels' radiance is "
            "diffuse: glossy=first)",
            fullPathReference("indirect")};
      }};
}

}  // namespace vgi
