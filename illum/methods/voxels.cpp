// `voxels`: the binary voxel grid seen from the camera — a debug view (the
// viewer's "binary grid" and "mip level" views, and `vgi render --method
// voxels`). Per sample, every pixel's jittered camera ray is traced through
// the OR-mip pyramid with the chosen tracer (VGI §4, Thiedemann et al. 2011:
// the same GLSL first-hit traversal the GI modules use); the first set
// voxel's entered face is coloured by its axis, shaded by |cos| to the ray and
// by distance, its cell edges outlined.
// What it shows is what the modules' rays hit: the chosen voxelizer at the
// chosen resolution. With level = l > 0 it traces the pyramid from level l up
// (pyramidFromLevel in shaders/shared/or_mip.glsl): each column of level l —
// the OR of 2^l × 2^l level-0 columns, the depth cells kept (VGI §4.1) — is
// drawn as one cell 2^l voxels wide in x and y, which shows how conservative
// the coarse levels the hierarchical tracer skips through are.
// It estimates no integral, so it has no exact counterpart.
//
// Needs: binary grid, OR-mip pyramid (no G-buffer).
//
// Parameters: `vgi render --help-module voxels` (and docs/PARAMETERS.md), generated from the
// ParamSet declarations (this file's and its kits'), whose doc strings are the one place they are written.
#include "illum/methods/voxels.h"

#include <glad/gl.h>

#include <algorithm>

#include "core/error.h"
#include "core/shader_library.h"
#include "illum/framework/compute_pass.h"
#include "illum/framework/sample_loop.h"
#include "illum/resources/or_mip_pyramid.h"
#include "shaders/illum/voxels/params.glsl"
#include "shaders/shared/bindings.glsl"
#include "traverse/gl_ray_tracer.h"

namespace vgi {

namespace {

class VoxelViewMethod : public Method {
 public:
  VoxelViewMethod(ParamSet& p, const Scene&) {
    tracer_ = readTracerParam(p, false);  // (a view of the voxels: bvh would show triangles)
    grid_ = readBinaryGridParams(p, 4);   // static + frame grid (atlas), the pyramid
    level_ = p.getInt("level", 0, "OR-mip level shown: 0 = the grid, l = columns of 2^l x 2^l voxels", 0,
                      int(shared::kMaxPyramidLevels) - 1);
  }
  SceneNeeds needs() const override {
    SceneNeeds n;
    n.add(OrMipPyramidNeed{grid_});
    return n;
  }
  void prepareFrame(Frame& f) override {
    ShaderDefines defs;
    addTracerDefine(defs, tracer_);
    view_.create(f, {"illum/voxels/view.comp.glsl"}, defs, {});
    const GlPyramid& pyramid = f.resources.get<GlPyramid>();
    if (uint32_t(level_) >= pyramid.levels()) {
      const glm::uvec3 r = pyramid.box().resolution;
      fail("parameter 'level': ", level_, " is not a level of the OR-mip pyramid over ", r.x, "x", r.y,
           " columns (levels 0 … ", pyramid.levels() - 1, ")");
    }
  }
  bool addSample(Frame& f, int) override {
    auto s = f.profiler.scope("trace_view");
    shared::VoxelViewParams& p = view_.params();
    for (int c = 0; c < 4; ++c) p.invViewProj[c] = f.camera.invViewProj[c];
    p.eye = glm::vec4(f.camera.position, f.camera.clipNear);
    p.forward = glm::vec4(f.camera.forward, 0.0f);
    // The depth cue's range: the scene's nearest and farthest points from the eye.
    const Bounds b = f.scene.bounds(f.request.time);
    const glm::vec3 e = f.camera.position, nearest = glm::clamp(e, b.lo, b.hi);
    const glm::vec3 farthest = glm::max(glm::abs(e - b.lo), glm::abs(e - b.hi));
    p.nearest = glm::length(e - nearest);
    p.farthest = glm::length(farthest);
    p.level = uint32_t(level_);
    view_.use(f);
    f.resources.get<GlPyramid>().bind(f.shaders(), view_.program());
    glBindImageTexture(IMAGE_SAMPLE, f.sampleImage("image"), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    view_.dispatch(f.width(), f.height());
    return true;
  }

 private:
  std::string tracer_;
  BinaryGridNeed grid_;
  int level_ = 0;
  ComputePass<shared::VoxelViewParams> view_;
};

}  // namespace

MethodInfo voxelViewMethod() {
  return {"voxels",
          "GL debug view: the binary grid from the camera through the tracer (VGI 4), faces coloured by axis",
          true, [](ParamSet& p, const Scene& s) -> std::unique_ptr<Method> {
            return std::make_unique<VoxelViewMethod>(p, s);
          }};
}

}  // namespace vgi
