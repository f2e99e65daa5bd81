// `voxels`: the binary voxel grid seen from the camera — a debug view (the
// viewer's "binary grid" view, and `vgi render --method voxels`). Per sample,
// every pixel's jittered camera ray is traced through the OR-mip pyramid with
// the chosen tracer (VGI §4, Thiedemann et al. 2011: the same GLSL first-hit
// traversal the GI modules use); the first set voxel's entered face is
// coloured by its axis and shaded by |cos| to the ray. What it shows is what
// the modules' rays hit: the chosen voxelizer at the chosen resolution.
// It estimates no integral, so it has no exact counterpart.
//
// Needs: binary grid, OR-mip pyramid (no G-buffer).
//
// Parameters
// | key       | type   | default      | meaning                                     |
// |-----------|--------|--------------|---------------------------------------------|
// | tracer    | string | hierarchical | hierarchical, dda or march (GLSL define)    |
// | voxels    | string | 128          | grid resolution N or WxHxD                  |
// | voxelizer | string | atlas        | binary voxelizer (see `vgi voxelize --help`) |
#include "illum/voxel_view.h"

#include <glad/gl.h>

#include <algorithm>

#include "core/shader_library.h"
#include "illum/sample_loop.h"
#include "shaders/shared/bindings.glsl"
#include "traverse/gl_ray_tracer.h"

namespace vgi {

namespace {

class VoxelViewMethod : public Method {
 public:
  VoxelViewMethod(ParamSet& p, const Scene&) {
    tracer_ = readTracerParam(p);
    grid_ = readBinaryGridParams(p, 4);  // static + frame grid (atlas), the pyramid
  }
  SceneNeeds needs() const override {
    SceneNeeds n;
    n.binaryGrid = grid_;
    n.orMipPyramid = true;
    return n;
  }
  void prepareFrame(Frame& f) override {
    ShaderDefines defs;
    addTracerDefine(defs, tracer_);
    prog_ = f.shaders().program({"illum/voxel_view/view.comp.glsl"}, defs);
  }
  bool addSample(Frame& f, int) override {
    auto s = f.profiler.scope("trace_view");
    ShaderLibrary& shaders = f.shaders();
    glUseProgram(prog_);
    f.resources.glPyramid().bind(shaders, prog_);
    shaders.setUniform(prog_, "uInvViewProj", f.camera.invViewProj);
    shaders.setUniform(prog_, "uEye", f.camera.position);
    shaders.setUniform(prog_, "uInvDiagonal",
                       1.0f / std::max(f.scene.bounds(f.request.time).diagonal(), 1e-30f));
    glBindImageTexture(IMAGE_SAMPLE, f.sampleImage("image"), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glDispatchCompute(GLuint((f.width() + 7) / 8), GLuint((f.height() + 7) / 8), 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    return true;
  }

 private:
  std::string tracer_;
  BinaryGridNeed grid_;
  unsigned prog_ = 0;
};

}  // namespace

std::unique_ptr<Method> createVoxelViewMethod(ParamSet& params, const Scene& scene) {
  return std::make_unique<VoxelViewMethod>(params, scene);
}

}  // namespace vgi
