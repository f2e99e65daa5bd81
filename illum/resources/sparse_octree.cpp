#include "illum/resources/sparse_octree.h"

#include <glad/gl.h>

#include <cmath>

#include "core/error.h"
#include "core/profiler.h"
#include "core/shader_library.h"
#include "traverse/gl_ray_tracer.h"
#include "voxelize/gpu_grid.h"

namespace vgi {

nlohmann::json SparseOctreeNeed::key() const {
  return {{"grid", grid.key()},
          {"radiance", coneRadianceName(radiance)},
          {"anisotropic", anisotropic},
          {"dilate", dilate},
          {"update_every", updateEvery}};
}

nlohmann::json SparseOctreeNeed::settings() const {
  return {{"light_maps", lightMaps ? lightMaps->key() : nlohmann::json(nullptr)},
          {"bias", bias},
          {"normal_offset", normalOffset},
          {"inject_small", injectSmall}};
}

bool SparseOctree::update(SceneResources& res, const ResourceNeed& need, Profiler& prof) {
  need_ = need.spec<SparseOctreeNeed>();
  const GridBox& box = res.get<GridBox>(need_.grid);
  const glm::vec3 v = box.voxelSize();
  voxel_ = std::max({v.x, v.y, v.z});
  const bool lit = injectsRadiance(need_.radiance);
  bool rebuilt = false;
  if (!octree_ || res.changed(need_.pyramid())) {
    if (octree_) ++gridChanges_;
    if (!octree_ || gridChanges_ % need_.updateEvery == 0) {
      octree_ = std::make_unique<SparseVoxelOctree>(box, need_.anisotropic, need_.dilate);
      octree_->build(res.get<GlPyramid>(need_.pyramid()).words(), res.shaders(), prof);
      if (lit) sums_.allocate(octree_->leafCount());
      rebuilt = true;
      lag_ = 0;
    } else {
      ++lag_;
    }
  }
  // With area lights the light maps follow the sample's lights: beginSample relights (fills).
  if (lit && res.sampleLights()) return rebuilt;
  if (!rebuilt && !(lit && res.changed(*need_.lightMaps)) && filledFor_ == need_.settings().dump())
    return false;
  fill(res, prof);
  return true;
}

bool SparseOctree::relight(SceneResources& res, const ResourceNeed&, Profiler& prof) {
  if (!injectsRadiance(need_.radiance)) return false;
  fill(res, prof);
  return true;
}

void SparseOctree::fill(SceneResources& res, Profiler& prof) {
  filledFor_ = need_.settings().dump();
  if (!injectsRadiance(need_.radiance)) {
    octree_->resolve(0, 0, 1.0f, res.shaders(), prof);
    return;
  }
  sums_.inject(res, octree_->box(), need_.radiance, *need_.lightMaps, need_.bias, need_.normalOffset,
               need_.injectSmall, octree_.get(), prof);
  octree_->resolve(sums_.counts(), sums_.sums(), sums_.radianceMax(), res.shaders(), prof);
}

void bindConeOctree(const SparseVoxelOctree& octree, ShaderLibrary& shaders, unsigned prog, float step) {
  octree.bind(shaders, prog);
  setGridUniforms(shaders, prog, octree.box());
  const glm::vec3 v = octree.box().voxelSize();
  shaders.setUniform(prog, "uVoxelSize", std::max({v.x, v.y, v.z}));
  shaders.setUniform(prog, "uMaxLod", float(octree.depth()));
  shaders.setUniform(prog, "uConeStep", step);
}

void SparseOctree::bind(ShaderLibrary& shaders, unsigned prog, float step) const {
  bindConeOctree(*octree_, shaders, prog, step);
}

nlohmann::json SparseOctree::stats() {
  nlohmann::json j = octree_->describe();
  if (injectsRadiance(need_.radiance)) {
    j["injection_bytes"] = sums_.bytes();  // the leaves' sums and counts
    j["bytes"] = j["bytes"].get<double>() + sums_.bytes();
    j["radiance_max"] = sums_.radianceMax();
    // Occupied leaves no injected sample reached (radiance=texels: the maps' holes).
    j["unreached_leaves"] = octree_->countUnreachedLeaves(sums_.counts());
  }
  j["radiance_source"] = coneRadianceName(need_.radiance);
  j["update_every"] = need_.updateEvery;
  j["lag_frames"] = lag_;
  return j;
}

ResourceKind sparseOctreeKind() {
  return {"sparse_octree",
          "the cone tracers' volume as a sparse voxel octree with 3x3x3 bricks and (anisotropic) filtering",
          [](const ResourceNeed& n) {
            const SparseOctreeNeed& c = n.spec<SparseOctreeNeed>();
            std::vector<ResourceNeed> d{c.pyramid()};
            if (injectsRadiance(c.radiance)) d.push_back(*c.lightMaps);
            return d;
          },
          [](const ResourceNeed& n, const SceneNeeds&, const std::string& method, bool gl) {
            const SparseOctreeNeed& c = n.spec<SparseOctreeNeed>();
            requireGl(n, method, gl);
            if (injectsRadiance(c.radiance) && !c.lightMaps)
              fail("method '", method,
                   "' asks for a sparse octree with radiance=", coneRadianceName(c.radiance),
                   " without light maps");
          },
          [](const ResourceNeed&) { return std::vector<std::string>{"sparse_octree"}; },
          [](const ResourceNeed& n, SceneResources&) -> std::unique_ptr<Resource> {
            return std::make_unique<SparseOctree>(n.spec<SparseOctreeNeed>());
          },
          "volume"};
}

const ResourceKind& SparseOctreeNeed::row() {
  static const ResourceKind k = sparseOctreeKind();
  return k;
}

}  // namespace vgi
