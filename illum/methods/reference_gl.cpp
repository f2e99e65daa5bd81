// `reference_gl` — the exact integrals of `reference` (illum/methods/reference.cpp)
// as a GL method, through the scene's triangles in a BVH on the GPU (resource
// kind gpu_bvh; shaders/shared/trace_bvh.glsl), so that an approximate GL
// method and its exact counterpart run on the same device and the
// equal-error time ratio compares algorithms, not a GPU with a CPU (DESIGN.md,
// "Exact counterparts"). A second implementation of the same estimators: its
// tests compare it with `reference` statistically (block means over seeds).
//
// Implemented so far: integrator=ao (reference's aoLi: the camera ray's first
// hit, one cosine-distributed direction about the shading normal per sample,
// visibility within the radius). path, direct and nearfield (materials,
// delta and area lights with NEE + MIS, Russian roulette, AOVs) are the next
// step; until then they are refused by name.
//
// | key        | type   | default       | meaning                                     |
// |------------|--------|---------------|---------------------------------------------|
// | integrator | string | ao            | what to compute: ao                          |
// | radius     | float  | 0.1 · diag.   | AO ray length, world units (as `reference`) |
#include "illum/methods/reference_gl.h"

#include <glad/gl.h>

#include "core/error.h"
#include "core/params.h"
#include "core/shader_library.h"
#include "illum/framework/deferred.h"
#include "illum/framework/sample_loop.h"
#include "illum/kits/shared_params.h"
#include "illum/resources/gpu_bvh.h"
#include "shaders/shared/bindings.glsl"
#include "traverse/gpu_bvh.h"

namespace vgi {

namespace {

class ReferenceGlMethod : public Method {
 public:
  ReferenceGlMethod(ParamSet& p, const Scene& scene) {
    p.getString("integrator", "ao",
                "what to compute: ao (the exact AO of reference integrator=ao; path, direct and nearfield "
                "are not implemented on the GL device yet)",
                {"ao"});
    const float diag = scene.bounds().diagonal();
    radius_ = p.getFloat("radius", kDefaultAoRadius * diag,
                         "AO ray length in world units (default 0.1 x scene diagonal, as reference)", 1e-30f,
                         1e30f);
    diagonal_ = diag;
  }
  SceneNeeds needs() const override {
    SceneNeeds n;
    n.add(GpuBvhNeed{});
    return n;
  }
  void prepareFrame(Frame& f) override {
    prog_ = f.shaders().program({"illum/reference_gl/ao.comp.glsl"});
    ShaderLibrary& s = f.shaders();
    s.setUniform(prog_, "uRadius", radius_);
    // The reference's start offset: 2e-5 of the scene's diagonal at this time (plus the coordinates' part).
    s.setUniform(prog_, "uEps", 2e-5f * f.scene.bounds(f.request.time).diagonal());
    s.setUniform(prog_, "uSeed", f.request.seed);
    // Pixel positions are drawn per sample in the shader, through the reference's pinhole camera
    // (not the sample loop's jittered projection).
    const PinholeView v = pinholeView(f.scene.camera, f.width(), f.height());
    s.setUniform(prog_, "uEye", v.position);
    s.setUniform(prog_, "uFwd", v.fwd);
    s.setUniform(prog_, "uRight", v.right * (v.tanHalf * v.aspect));
    s.setUniform(prog_, "uUp", v.up * v.tanHalf);
  }
  bool addSample(Frame& f, int k) override {
    auto scope = f.profiler.scope("ao");
    ShaderLibrary& s = f.shaders();
    glUseProgram(prog_);
    f.resources.get<GpuBvh>().bind();
    s.setUniform(prog_, "uSample", uint32_t(k));
    glBindImageTexture(IMAGE_SAMPLE, f.sampleImage("image"), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glDispatchCompute(unsigned(f.width() + 7) / 8, unsigned(f.height() + 7) / 8, 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    return true;
  }
  void finishFrame(Frame& f) override {
    f.extra["radius"] = radius_;
    f.extra["scene_diagonal"] = diagonal_;
  }

 private:
  float radius_ = 0, diagonal_ = 0;
  unsigned prog_ = 0;
};

}  // namespace

MethodInfo referenceGlMethod() {
  return {"reference_gl", "GL exact integrals through the scene's BVH on the GPU: integrator=ao (so far)",
          true, [](ParamSet& p, const Scene& s) -> std::unique_ptr<Method> {
            return std::make_unique<ReferenceGlMethod>(p, s);
          }};
}

}  // namespace vgi
