// The CPU side of the tracers: the shared GLSL/C++ kernels compiled as C++ and
// run over ray batches on all cores, plus Embree behind the same interface.
#include "traverse/ray_tracers.h"

#include <algorithm>

#include "core/error.h"
#include "core/parallel.h"
#include "shaders/shared/trace_bricks.glsl"
#include "shaders/shared/trace_dda.glsl"
#include "shaders/shared/trace_hierarchical.glsl"
#include "shaders/shared/trace_march.glsl"
#include "shaders/shared/tracer_ids.glsl"
#include "traverse/brick_tree.h"
#include "traverse/embree_tracer.h"
#include "traverse/gpu_bvh.h"
#include "traverse/or_mip_pyramid.h"

namespace vgi {

const std::vector<TracerInfo>& tracerRegistry() {
  static const std::vector<TracerInfo> registry = {
      {"hierarchical", "first hit over the OR-mip pyramid (VGI §4)", true, VGI_TRACER_HIERARCHICAL},
      {"dda", "3D DDA over the finest grid (Amanatides & Woo 1987); the oracle on the grid", true,
       VGI_TRACER_DDA},
      {"march", "fixed-step ray marching (AVG paper); step = half the smallest voxel edge", true,
       VGI_TRACER_MARCH},
      {"bvh",
       "exact first hit on the triangles through a BVH built by Embree's builder (watertight, Woop et al. "
       "2013); "
       "GLSL and C++",
       true, VGI_TRACER_BVH},
      {"embree", "exact first hit on the triangles (Embree, CPU only)", false, -1},
      {"bricks", "first hit through 4³ bricks, a 64-tree over dense levels (C++ only so far)", false, -1},
  };
  return registry;
}

const TracerInfo& findTracer(const std::string& name, const std::string& what) {
  std::string names;
  for (const TracerInfo& t : tracerRegistry()) {
    if (t.name == name) return t;
    names += (names.empty() ? "" : ", ") + t.name;
  }
  fail(what, " '", name, "': unknown tracer (choose from ", names, ")");
}

shared::PyramidParams pyramidParams(const GridBox& box) {
  shared::PyramidParams p{};
  p.grid = box.params();
  uint32_t total = 0;
  std::vector<uint32_t> offsets = OrMipPyramid::layout(box, total);
  if (offsets.size() > shared::kMaxPyramidLevels)
    fail("OR-mip pyramid: ", offsets.size(), " levels, at most ", shared::kMaxPyramidLevels, " supported");
  p.levels = uint32_t(offsets.size());
  for (uint32_t l = 0; l < p.levels; ++l) p.levelOffsets[l] = offsets[l];
  return p;
}

shared::PyramidParams pyramidParams(const OrMipPyramid& pyramid) { return pyramidParams(pyramid.box()); }

float defaultMarchStep(const GridBox& box) {
  glm::vec3 v = box.voxelSize();
  return 0.5f * std::min(v.x, std::min(v.y, v.z));
}

float defaultMarchStep(const OrMipPyramid& pyramid) { return defaultMarchStep(pyramid.box()); }

void RayTracer::traceBatch(const std::vector<TraceRay>& rays, std::vector<TraceResult>& out,
                           int threads) const {
  out.resize(rays.size());
  parallelFor(rays.size(), 4096, threads, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) out[i] = trace(rays[i]);
  });
}

void RayTracer::countBatch(const std::vector<TraceRay>& rays, std::vector<TraceResult>& out,
                           std::vector<shared::TraceCounts>& counts, int threads) const {
  out.resize(rays.size());
  counts.assign(rays.size(), shared::TraceCounts{});
  parallelFor(rays.size(), 4096, threads, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      shared::traceCounts = &counts[i];
      out[i] = trace(rays[i]);
    }
    shared::traceCounts = nullptr;
  });
}

namespace {

TraceResult fromShared(const shared::TraceHit& h) {
  TraceResult r;
  r.hit = h.hit != 0u;
  r.t = h.t;
  r.voxel = h.voxel;
  r.steps = h.steps;
  return r;
}

class VoxelTracer : public RayTracer {
 public:
  VoxelTracer(int kind, const OrMipPyramid& pyramid, float marchStep, uint32_t level)
      : kind_(kind),
        params_(shared::pyramidFromLevel(pyramidParams(pyramid), level)),
        words_(pyramid.words().data()),
        marchStep_(marchStep) {}
  TraceResult trace(const TraceRay& ray) const override {
    switch (kind_) {
      case VGI_TRACER_HIERARCHICAL:
        return fromShared(shared::traceHierarchical(params_, ray.origin, ray.dir, ray.tmax, words_));
      case VGI_TRACER_DDA:
        return fromShared(shared::traceDda(params_, ray.origin, ray.dir, ray.tmax, words_));
      case VGI_TRACER_MARCH:
        return fromShared(shared::traceMarch(params_, ray.origin, ray.dir, ray.tmax, marchStep_, words_));
    }
    VGI_CHECK(!"unknown tracer id");
    return {};
  }

 private:
  int kind_;
  shared::PyramidParams params_;
  const uint32_t* words_;
  float marchStep_;
};

// The 4³ bricks' tracer over a tree it builds from the pyramid's grid (shared/trace_bricks.glsl).
class BrickRayTracer : public RayTracer {
 public:
  explicit BrickRayTracer(const OrMipPyramid& pyramid) : tree_(pyramid) {}
  TraceResult trace(const TraceRay& ray) const override {
    return fromShared(shared::traceBricks(tree_.params(), ray.origin, ray.dir, ray.tmax, tree_.gridWords(),
                                          tree_.words().data()));
  }

 private:
  BrickTree tree_;
};

// A tracer of the triangles: the hit's distance to the surface, and the grid
// cell that holds the hit point (when a grid is given).
class TriangleRayTracer : public RayTracer {
 public:
  explicit TriangleRayTracer(const OrMipPyramid* pyramid) {
    if (pyramid) {
      grid_ = pyramid->box().params();
      hasGrid_ = true;
    }
  }

 protected:
  TraceResult hitAt(const TraceRay& ray, float t, uint32_t steps) const {
    TraceResult r;
    r.hit = true;
    r.t = t;
    r.steps = steps;
    if (hasGrid_) r.voxel = shared::gridCell(grid_, shared::worldToGrid(grid_, ray.origin + t * ray.dir));
    return r;
  }

 private:
  shared::GridParams grid_{};
  bool hasGrid_ = false;
};

class EmbreeRayTracer : public TriangleRayTracer {
 public:
  EmbreeRayTracer(const EmbreeTracer& embree, const OrMipPyramid* pyramid)
      : TriangleRayTracer(pyramid), embree_(embree) {}
  TraceResult trace(const TraceRay& ray) const override {
    if (!(ray.tmax >= 0.0f)) return {};
    TriangleHit h = embree_.firstHit(ray.origin, ray.dir, 0.0f, ray.tmax);
    return h.hit ? hitAt(ray, h.t, 0) : TraceResult{};
  }

 private:
  const EmbreeTracer& embree_;
};

// The shared BVH kernel, as tracer=bvh runs it in GLSL (traverse/tracer.glsl).
class BvhRayTracer : public TriangleRayTracer {
 public:
  BvhRayTracer(const BvhArrays& bvh, const OrMipPyramid* pyramid) : TriangleRayTracer(pyramid), bvh_(bvh) {}
  TraceResult trace(const TraceRay& ray) const override {
    const shared::BvhHit h = traceBvhCpu(bvh_, ray.origin, ray.dir, ray.tmax, false);
    if (h.hit) return hitAt(ray, h.t, h.steps);
    TraceResult miss;
    miss.steps = h.steps;
    return miss;
  }

 private:
  const BvhArrays& bvh_;
};

}  // namespace

std::unique_ptr<RayTracer> createTracer(const std::string& name, const TracerInputs& in) {
  const TracerInfo& info = findTracer(name);
  if (info.name == "bvh") {
    if (!in.bvh) fail("tracer 'bvh' needs the scene's BVH");
    return std::make_unique<BvhRayTracer>(*in.bvh, in.pyramid);
  }
  if (info.name == "embree") {
    if (!in.embree) fail("tracer 'embree' needs the scene's triangles");
    return std::make_unique<EmbreeRayTracer>(*in.embree, in.pyramid);
  }
  if (!in.pyramid) fail("tracer '", name, "' needs a voxel grid");
  if (info.name == "march" && in.marchStep < 0.0f) fail("march step ", in.marchStep, " must be > 0");
  if (in.level >= uint32_t(in.pyramid->levels()))
    fail("tracer '", name, "': level ", in.level, " is not a level of the pyramid (0 … ",
         in.pyramid->levels() - 1, ")");
  if (info.name == "bricks") {
    if (in.level != 0) fail("tracer 'bricks' traces the grid itself (level 0), not level ", in.level);
    return std::make_unique<BrickRayTracer>(*in.pyramid);
  }
  float step = in.marchStep > 0.0f ? in.marchStep : defaultMarchStep(*in.pyramid);
  return std::make_unique<VoxelTracer>(info.define, *in.pyramid, step, in.level);
}

}  // namespace vgi
