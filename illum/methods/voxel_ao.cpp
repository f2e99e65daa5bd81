// `voxel_ao`: ambient occlusion with the hierarchical first-hit tracer of
// Thiedemann et al., "Voxel-based Global Illumination" (I3D 2011, §4: the
// OR-mip pyramid traversal) over the binary voxel grid — the visibility half
// of VGI's near-field gathering (§5.1) with a constant "light": AO(x) is the
// cosine-weighted fraction of directions along which no voxel lies within
// the radius r. Rays start `offset` voxel diagonals along the normal; with
// `passthrough`, hits within a voxel diagonal of the receiver's tangent plane
// are passed (they may be the receiver's own voxels), as in nearfield.
//
// Needs: G-buffer, binary grid, OR-mip pyramid. Per sample: the gather kit's
// interleaved cosine rays at 1, ½ or ¼ resolution (shaders/illum/voxel_ao/
// ao.comp) → geometry-aware blur → joint bilateral upsampling; pixels that
// see no surface are 0.
//
// The exact counterpart is `reference --set integrator=ao` with the same
// `radius` (Embree visibility of the same cosine rays from the surface): the
// difference is the voxelization (conservative cells stand in for
// triangles), the start offset and passed band, and the reduced resolution
// with its blur and upsampling.
//
// Parameters: `vgi render --help-module voxel_ao` (and docs/PARAMETERS.md), generated from the
// ParamSet declarations (this file's and its kits'), whose doc strings are the one place they are written.
#include "illum/methods/voxel_ao.h"

#include <glad/gl.h>

#include "core/shader_library.h"
#include "illum/framework/compute_pass.h"
#include "illum/framework/sample_loop.h"
#include "illum/kits/gather_kit.h"
#include "illum/kits/shared_params.h"
#include "illum/kits/tracer_kit.h"
#include "illum/resources/gpu_scene.h"
#include "illum/resources/or_mip_pyramid.h"
#include "shaders/illum/voxel_ao/params.glsl"
#include "traverse/gl_ray_tracer.h"

namespace vgi {

namespace {

class VoxelAoMethod : public Method {
 public:
  VoxelAoMethod(ParamSet& p, const Scene& scene) {
    radius_ =
        p.getFloat("radius", kDefaultAoRadius * scene.bounds().diagonal(),
                   "ray length r in world units (default 0.1 x scene diagonal, as reference integrator=ao)",
                   1e-30f, 1e30f);
    gather_ = readGatherParams(p, "AO", false);
    tracer_ = readTracerParam(p);
    offset_ = readOffset(p);
    temporal_ = readTemporal(p);
    passThrough_ = readPassThrough(p, "it lies within a voxel diagonal of the receiver's plane");
    grid_ = readBinaryGridParams(p, 4);  // static + frame grid (atlas), the pyramid (≈ 4/3 of a grid)
  }
  SceneNeeds needs() const override {
    SceneNeeds n;
    needGBuffer(n);
    addTracerNeeds(n, grid_, tracer_);
    return n;
  }
  void prepareFrame(Frame& f) override {
    kit_.prepare(f, gather_);
    ShaderDefines defs;
    addTracerDefine(defs, tracer_);
    ao_.create(f, {"illum/voxel_ao/ao.comp.glsl"}, defs, {gbufferInput});
    const float diagonal = f.resources.get<GridBox>().voxelDiagonal();
    GatherKit::checkPass(ao_);
    shared::VoxelAoParams& p = ao_.params();
    p.radius = radius_;
    p.offset = offset_ * diagonal;
    p.voxelDiagonal = diagonal;
    p.passThrough = passThrough_ ? 1 : 0;
  }
  bool addSample(Frame& f, int k) override {
    {
      auto s = f.profiler.scope("ao");
      ao_.use(f);
      bindTracer(f.resources, f.shaders(), ao_.program());
      kit_.setSample(k, f.request.seed);
      kit_.dispatchGather(kit_.settings().rays, GatherKit::kRaysPerDispatch);
    }
    kit_.resolve(f);
    return true;
  }
  void finishFrame(Frame& f) override {
    f.extra["radius"] = radius_;
    f.extra["offset_world"] = offset_ * f.resources.get<GridBox>().voxelDiagonal();
    f.extra["ao_size"] = {kit_.width(), kit_.height()};
    f.extra["blur_window_px"] = kit_.blurWindow();
  }

  TemporalSettings temporal() const override { return temporal_; }

 private:
  TemporalSettings temporal_;
  float radius_ = 0, offset_ = 0.5f;
  bool passThrough_ = true;
  GatherSettings gather_;
  std::string tracer_;
  BinaryGridNeed grid_;
  GatherKit kit_;
  ComputePass<shared::VoxelAoParams> ao_;
};

}  // namespace

MethodInfo voxelAoMethod() {
  return {
      "voxel_ao", "GL ambient occlusion through the binary voxel grid (hierarchical first-hit tracer, VGI 4)",
      true,
      [](ParamSet& p, const Scene& s) -> std::unique_ptr<Method> {
        return std::make_unique<VoxelAoMethod>(p, s);
      },
      [](const nlohmann::json& p) {
        // Occlusion within the radius is the quantity itself: the model leaves nothing out.
        const std::vector<std::string> ao = {"integrator=ao", "radius=" + counterpartText(p.at("radius"))};
        return Counterpart{"reference", ao, {}, "", ao};
      }};
}

}  // namespace vgi
