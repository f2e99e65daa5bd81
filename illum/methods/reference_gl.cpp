// `reference_gl` — the exact integrals of `reference` (illum/methods/reference.cpp)
// as a GL method, through the scene's triangles in a BVH on the GPU (resource
// kind gpu_bvh; shaders/shared/trace_bvh.glsl), so that an approximate GL
// method and its exact counterpart run on the same device and the
// equal-error time ratio compares algorithms, not a GPU with a CPU (DESIGN.md,
// "Exact counterparts"). A second implementation of the same estimators, with
// the same parameters (illum/kits/exact_params.h): its tests compare it with
// `reference` statistically (block means over seeds).
//
//   path, direct, nearfield  shaders/illum/reference_gl/path.comp.glsl: materials
//              and textures of the GPU scene, delta lights, area lights
//              (resource kind gpu_emitters) by NEE + BRDF sampling with MIS,
//              Russian roulette, the "direct" / "indirect" outputs
//   ao         shaders/illum/reference_gl/ao.comp.glsl
//
// Not on the GL device: visibility=voxels (the voxel-visibility stage of the
// error split runs in `reference`, CPU), refused by name.
//
// Random numbers: one 32-bit PCG stream per (pixel, sample, seed)
// (shared/sampling.glsl), not the CPU reference's 64-bit PCG32, so the two
// agree in expectation, not per pixel.
#include "illum/methods/reference_gl.h"

#include <glad/gl.h>

#include "core/emitters.h"
#include "core/error.h"
#include "core/gpu_scene.h"
#include "core/params.h"
#include "core/shader_library.h"
#include "illum/framework/compute_pass.h"
#include "illum/framework/deferred.h"
#include "illum/framework/sample_loop.h"
#include "illum/kits/exact_params.h"
#include "illum/resources/gpu_bvh.h"
#include "illum/resources/gpu_emitters.h"
#include "illum/resources/gpu_scene.h"
#include "shaders/illum/reference_gl/params.glsl"
#include "shaders/shared/bindings.glsl"
#include "traverse/gpu_bvh.h"

namespace vgi {

static_assert(int(GlossyModel::All) == GLOSSY_ALL && int(GlossyModel::First) == GLOSSY_FIRST &&
                  int(GlossyModel::Direct) == GLOSSY_DIRECT,
              "exact_params.h's GlossyModel is the shader's GLOSSY_*");

namespace {

class ReferenceGlMethod : public Method {
 public:
  ReferenceGlMethod(ParamSet& p, const Scene& scene)
      : p_(readExactParams(p, scene, "reference_gl", false)), diagonal_(scene.bounds().diagonal()) {}
  SceneNeeds needs() const override {
    SceneNeeds n;
    n.add(GpuBvhNeed{});
    if (p_.integrator != ExactIntegrator::Ao) {
      n.add(GpuSceneNeed{});
      n.add(GpuEmittersNeed{});
    }
    return n;
  }
  std::vector<std::string> outputs() const override {
    return p_.splitsDirectIndirect() ? std::vector<std::string>{"direct", "indirect"}
                                     : std::vector<std::string>{};
  }
  void prepareFrame(Frame& f) override {
    shared::ReferenceGlParams& p = pass_.params();
    if (p_.integrator == ExactIntegrator::Ao) {
      pass_.create(f, {"illum/reference_gl/ao.comp.glsl"}, {}, {});
    } else {
      ShaderDefines defs;
      if (p_.integrator == ExactIntegrator::NearField) defs["REFERENCE_NEARFIELD"] = "1";
      pass_.create(f, {"illum/reference_gl/path.comp.glsl"}, defs, {gpuSceneInput});
      p.maxDepth = p_.maxDepth;
      p.rrDepth = p_.rrDepth;
      p.env = p_.env ? 1 : 0;
      p.envIndirect = p_.envIndirect ? 1 : 0;
      // The scene's own delta lights are the first entries of the GPU scene's lights.
      p.deltaLights = int(f.scene.lights.size());
      p.emitterCount = int(f.resources.get<GpuEmitters>().count());
      p.emitterSampling = p_.emitterSampling == EmitterSampling::Mis     ? shared::EMITTER_SAMPLING_MIS
                          : p_.emitterSampling == EmitterSampling::Light ? shared::EMITTER_SAMPLING_LIGHT
                                                                         : shared::EMITTER_SAMPLING_BRDF;
      p.writeIndirect = f.wants("indirect") ? 1 : 0;
      p.writeDirect = f.wants("direct") ? 1 : 0;
      p.glossy = int(p_.glossy);
    }
    p.radius = p_.radius;
    // The reference's start offset: 2e-5 of the scene's diagonal at this time (plus the coordinates' part).
    p.eps = 2e-5f * f.scene.bounds(f.request.time).diagonal();
    p.seed = f.request.seed;
    // Pixel positions are drawn per sample in the shader, through the reference's pinhole camera
    // (not the sample loop's jittered projection).
    const PinholeView v = pinholeView(f.scene.cameraAt(f.request.time), f.width(), f.height());
    p.eye = glm::vec4(v.position, v.clipNear);
    p.forward = glm::vec4(v.fwd, 0.0f);
    p.right = glm::vec4(v.right * (v.tanHalf * v.aspect), 0.0f);
    p.up = glm::vec4(v.up * v.tanHalf, 0.0f);
  }
  bool addSample(Frame& f, int k) override {
    auto scope = f.profiler.scope(p_.integratorName);
    pass_.params().sampleIndex = uint32_t(k);
    pass_.use(f);
    f.resources.get<GpuBvh>().bind();
    if (p_.integrator != ExactIntegrator::Ao) {
      f.resources.get<GpuScene>().bindVertices();
      f.resources.get<GpuEmitters>().bind();
    }
    bindSampleAndSplitImages(f);
    pass_.dispatch(f.width(), f.height());
    return true;
  }
  void finishFrame(Frame& f) override {
    if (p_.integrator == ExactIntegrator::Ao || p_.integrator == ExactIntegrator::NearField)
      f.extra["radius"] = p_.radius;
    f.extra["scene_diagonal"] = diagonal_;
    if (p_.integrator != ExactIntegrator::Ao)
      f.extra["emitter_triangles"] = f.resources.get<GpuEmitters>().count();
  }

 private:
  ExactParams p_;
  float diagonal_ = 0;
  ComputePass<shared::ReferenceGlParams> pass_;
};

}  // namespace

MethodInfo referenceGlMethod() {
  return {"reference_gl",
          "GL exact integrals through the scene's BVH on the GPU (reference on the GL device): "
          "integrator=path|nearfield|ao|direct",
          true, [](ParamSet& p, const Scene& s) -> std::unique_ptr<Method> {
            return std::make_unique<ReferenceGlMethod>(p, s);
          }};
}

}  // namespace vgi
