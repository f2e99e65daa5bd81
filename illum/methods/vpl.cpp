// `vpl`: instant radiosity (Keller 1997) with voxel visibility, as in
// Thiedemann et al., "Voxel-based Global Illumination" (I3D 2011, §5.3).
// Per sample:
//   1. direct light of the G-buffer point (the deferred pass, as `direct`);
//   2. the flux tree of the reflective shadow maps (shaders/illum/vpl/
//      flux_tree.comp; shared/vpl.glsl) and N VPL chains
//      (shaders/illum/vpl/generate.comp): first-bounce VPLs at RSM texels
//      drawn proportionally to their reflected flux (Dachsbacher and
//      Stamminger 2005; importance-sampled, stratified by a rotated R2
//      sequence), then `bounces` − 1 further VPLs per chain, each at the first
//      hit of a cosine-distributed ray through the voxel grid (hierarchical
//      first hit), normal and albedo from the multi-valued grids;
//   3. the gather (shaders/illum/vpl/gather.comp) in the gather kit's buffer
//      (illum/kits/gather_kit.h: ½ resolution by default, k×k interleaved subsets
//      of the chains, VGI/Keller–Heidrich deferred + interleaved sampling),
//      with the two-point visibility test through the OR-mip pyramid (§4.1)
//      and the geometry term's 1/d² clamped at d ≥ clamp · the scene's
//      diagonal; the kit's geometry-aware blur over the k×k window and joint
//      bilateral upsampling composite albedo × the gathered light into the
//      sample.
// Each sample draws a new VPL set, so the sample loop's average converges to
// the clamped many-light estimate.
//
// Light transport: direct light plus `bounces` diffuse interreflections —
// the exact counterpart is `reference integrator=path maxdepth=bounces+1`.
// The VPLs and receivers reflect diffusely (the Phong lobes of glossy
// materials are not part of this method's integral: on a glossy scene the
// difference is error). The error against the counterpart splits into:
//   clamp        the energy the geometry clamp removes (clamp=0: none);
//   visibility   voxel two-point tests — visibility=exact gathers from the
//                same VPLs (same seed: the same generation pass) with Embree
//                occlusion rays on the CPU, visibility=none with none;
//   VPL tracing  bounce VPLs placed through the voxel grid (hit point, the
//                cell's mean normal and albedo);
//   the RSM      texel resolution (a VPL stands for a texel's area).
//
// Parameters: `vgi render --help-module vpl` (and docs/PARAMETERS.md), generated from the
// ParamSet declarations (this file's and its kits'), whose doc strings are the one place they are written.
#include "illum/methods/vpl.h"

#include <glad/gl.h>

#include <nlohmann/json.hpp>

#include "core/gl_handles.h"
#include "core/gpu_scene.h"
#include "core/shader_library.h"
#include "illum/framework/deferred.h"
#include "illum/framework/sample_loop.h"
#include "illum/kits/direct_pass.h"
#include "illum/kits/shared_params.h"
#include "illum/kits/tracer_kit.h"
#include "illum/kits/vpl_kit.h"
#include "illum/resources/bvh.h"
#include "illum/resources/gpu_scene.h"
#include "illum/resources/light_maps.h"
#include "illum/resources/or_mip_pyramid.h"
#include "illum/resources/value_grids.h"
#include "shaders/shared/bindings.glsl"
#include "shaders/shared/vpl.glsl"
#include "traverse/gl_ray_tracer.h"
#include "voxelize/value_textures.h"

namespace vgi {

namespace {

class VplMethod : public Method {
 public:
  VplMethod(ParamSet& p, const Scene& scene) {
    readVplParams(p, s_);
    s_.bounces = p.getInt("bounces", 2,
                          "VPLs per chain: 1 = the RSM texels' VPLs only (one indirect bounce); "
                          "each further one at the first voxel hit of a diffuse bounce ray",
                          1, 16);
    const std::string visibility =
        p.getString("visibility", "voxels",
                    "VPL visibility: voxels (VGI 4.1 two-point test through the OR-mip pyramid), "
                    "exact (Embree occlusion rays on the CPU, from the same VPLs) or none",
                    {"voxels", "exact", "none"});
    s_.visibility = visibility == "voxels"  ? VplVisibility::Voxels
                    : visibility == "exact" ? VplVisibility::Exact
                                            : VplVisibility::None;
    s_.offset = p.getFloat("offset", 1.0f,
                           "two-point test: receiver and VPL moved along their normals, in voxel diagonals",
                           0.0f, 100.0f);
    bounceOffset_ = p.getFloat("bounce_offset", 0.5f,
                               "bounce rays' start offset along the VPL's normal, in voxel diagonals "
                               "(own-band hits are passed, as in voxelpath)",
                               0.0f, 100.0f);
    tracer_ = readTracerParam(p);
    // The gather kit's wall remedies trace the voxels: with voxel visibility only. Off by default here:
    // they stop the leak but cost noise where nothing leaks (docs/BENCHMARKS.md, "Remedies").
    readGatherWallParams(p, s_.gather, false, false);
    if (s_.visibility != VplVisibility::Voxels && (s_.gather.visibility || s_.gather.fixup))
      fail("parameters 'blur_visibility' and 'fixup' trace the voxels: they need visibility=voxels, not '",
           visibility, "'");
    // Static + frame grid, the pyramid (≈ 4/3 of a grid); the value grids (≈ 2 more) are checked when built.
    checkVplMemory(s_);
    grid_ = readBinaryGridParams(p, 4, s_.bounces > 1);
    readShadowParams(p, shadow_);
    temporal_ = readTemporal(p);
    diagonal_ = scene.bounds().diagonal();
  }
  std::vector<std::string> outputs() const override { return {"direct", "indirect"}; }
  SceneNeeds needs() const override {
    SceneNeeds n;
    needGBuffer(n);
    n.add(LightMapNeed{shadow_.resolution, true});
    if (s_.bounces > 1)
      addVoxelHitNeeds(n, grid_, tracer_, {"normal", "albedo"});
    else if (s_.visibility == VplVisibility::Voxels)
      addTracerNeeds(n, grid_, tracer_);
    if (s_.visibility == VplVisibility::Exact) n.add(BvhNeed{});
    return n;
  }
  void prepareFrame(Frame& f) override {
    ShaderLibrary& shaders = f.shaders();
    const GridBox* box = f.resources.tryGet<GridBox>();
    voxelDiagonal_ = box ? box->voxelDiagonal() : 0.0f;
    direct_ = std::make_unique<DirectPass>(shaders, f.resources.get<GpuScene>(), shadow_.bias,
                                           shadow_.normalOffset);
    kit_.prepare(f, s_, tracer_, voxelDiagonal_, diagonal_);
    ShaderDefines defs;
    addTracerDefine(defs, tracer_);
    fluxProg_ = shaders.program({"illum/vpl/flux_tree.comp.glsl"});
    genProg_ = shaders.program({"illum/vpl/generate.comp.glsl"}, defs);
    res_ = unsigned(shadow_.resolution);
    shaders.setUniform(fluxProg_, "uRes", res_);
    shaders.setUniform(genProg_, "uRes", res_);
    shaders.setUniform(genProg_, "uChains", unsigned(s_.chains));
    shaders.setUniform(genProg_, "uBounces", s_.bounces);
    shaders.setUniform(genProg_, "uSeed", f.request.seed);
    // The bounce rays: voxelpath's first-hit rule and hit vertex (illum/voxel_hits.glsl), diffuse.
    shared::VoxelHitParams h{};
    h.offset = bounceOffset_ * voxelDiagonal_;
    h.voxelDiagonal = voxelDiagonal_;
    h.traceLength = 4.0f * diagonal_ + 1e-6f;
    h.glossy = 0;
    h.backProjection = shared::BACK_PROJECTION_PLANE;
    h.passThrough = 1;
    h.hitPoint = shared::VOXEL_HIT_ENTRY;
    hits_.set(genProg_, h);
  }
  bool addSample(Frame& f, int k) override {
    ShaderLibrary& shaders = f.shaders();
    const unsigned sample = f.sampleImage("image");
    {
      auto s = f.profiler.scope("direct");
      direct_->shade(f.gbuffer(), f.resources.get<LightMaps>(), f.camera, sample);
    }
    if (f.resources.get<LightMaps>().renders() != fluxRenders_) {
      // Only when the maps were drawn again (once per frame for delta lights, per sample for area lights).
      auto s = f.profiler.scope("flux_tree");
      buildFluxTree(f);
      fluxRenders_ = f.resources.get<LightMaps>().renders();
    }
    {
      auto s = f.profiler.scope("vpls");
      glUseProgram(genProg_);
      bindGrid(f, genProg_);
      hits_.bind();
      shaders.setUniform(genProg_, "uSampleIndex", uint32_t(k));
      shaders.setUniform(genProg_, "uRotation", vplRotation(k, f.request.seed));
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VPLS, kit_.vplBuffer());
      glDispatchCompute(unsigned(s_.chains + 63) / 64, 1, 1);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    {
      auto s = f.profiler.scope("gather");
      kit_.gather(f, [&](unsigned prog) {
        if (s_.visibility == VplVisibility::Voxels) bindTracer(f.resources, shaders, prog);
      });
    }
    kit_.resolve(f, [&](unsigned prog) {
      if (s_.visibility == VplVisibility::Voxels) bindTracer(f.resources, shaders, prog);
    });
    return true;
  }
  void finishFrame(Frame& f) override {
    kit_.stats(f);
    // Light the maps reflect but no VPL carries is a wrong image, not a dark scene: refuse it (zink once
    // placed none here and the render showed direct light only, exit 0).
    const double flux = fluxTotal();
    f.extra["vpl_flux_total"] = flux;
    if (flux > 0.0 && s_.chains > 0 && f.extra["vpls_placed"][0].get<uint64_t>() == 0)
      fail("vpl: the light maps reflect flux ", flux,
           " but the generation pass placed no VPL on this driver (",
           reinterpret_cast<const char*>(glGetString(GL_RENDERER)),
           "): the image would hold direct light only and was not written");
    f.addStateBytes(double(fluxFloats_ * sizeof(float)));  // the flux tree
    f.extra["voxel_diagonal"] = voxelDiagonal_;
  }

  TemporalSettings temporal() const override { return temporal_; }

 private:
  TemporalSettings temporal_;
  void bindGrid(Frame& f, unsigned prog) const {
    f.resources.get<GpuScene>().bind(f.shaders(), prog);
    f.resources.get<LightMaps>().bind();
    if (f.resources.tryGet<GlPyramid>()) bindTracer(f.resources, f.shaders(), prog);
    if (const ValueTextures* values = f.resources.tryGet<ValueTextures>()) values->bind();
  }

  // The flux the light maps reflect: the sum of every face's top node (one float read per face).
  double fluxTotal() const {
    if (fluxFloats_ == 0) return 0.0;
    const size_t stride = shared::fluxTreeFaceStride(res_);
    const size_t top = shared::fluxTreeOffset(res_, shared::fluxTreeLevels(res_) - 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    double sum = 0.0;
    for (size_t face = 0; face < fluxFloats_ / stride; ++face) {
      float v = 0.0f;
      glGetNamedBufferSubData(flux_.get(), GLintptr((face * stride + top) * sizeof(float)), sizeof v, &v);
      sum += double(v);
    }
    return sum;
  }

  // Level 0 from the RSMs, then each level from the one below (shared/vpl.glsl).
  void buildFluxTree(Frame& f) {
    ShaderLibrary& shaders = f.shaders();
    const unsigned faces = unsigned(f.resources.get<LightMaps>().faceCount());
    const size_t floats = size_t(faces) * shared::fluxTreeFaceStride(res_);
    if (floats != fluxFloats_) {
      flux_ = makeBuffer(std::max<size_t>(1, floats) * sizeof(float));
      fluxFloats_ = floats;
    }
    glUseProgram(fluxProg_);
    f.resources.get<GpuScene>().bind(shaders, fluxProg_);
    f.resources.get<LightMaps>().bind();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VPL_FLUX, flux_.get());
    for (unsigned l = 0; l < shared::fluxTreeLevels(res_); ++l) {
      const unsigned s = shared::fluxTreeSize(res_, l);
      shaders.setUniform(fluxProg_, "uLevel", l);
      glDispatchCompute((s + 7) / 8, (s + 7) / 8, faces);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
  }

  VplSettings s_;
  float bounceOffset_ = 0.5f, diagonal_ = 0, voxelDiagonal_ = 0;
  std::string tracer_;
  BinaryGridNeed grid_;
  ShadowParams shadow_;
  std::unique_ptr<DirectPass> direct_;
  VplKit kit_;
  unsigned fluxProg_ = 0, genProg_ = 0, res_ = 0;
  VoxelHits hits_;
  GlBuffer flux_;
  size_t fluxFloats_ = 0;
  uint64_t fluxRenders_ = ~uint64_t(0);
};

}  // namespace

MethodInfo vplMethod() {
  return {"vpl",
          "GL instant radiosity: RSM + voxel-traced VPL chains, voxel two-point visibility, interleaved (VGI "
          "5.3)",
          true,
          [](ParamSet& p, const Scene& s) -> std::unique_ptr<Method> {
            return std::make_unique<VplMethod>(p, s);
          },
          vplChainsCounterpart};
}

}  // namespace vgi
