// Resource kind "sparse_octree": the cone tracers' volume as a sparse voxel
// octree (voxelize/sparse_octree.h; Crassin et al. 2011, the 2013 article
// ../shared/papers/002_…, Dinse 2015 ch. 4–5), `vct`/`vct_ao` volume=svo: the
// same radiance and opacity as the dense cone_volume (illum/resources/cone_volume.h)
// at the same leaf resolution, in the storage of the papers. Built from the
// binary grid of any voxelizer (its occupied cells are the fragments), its
// leaves lit by the same injection (radiance=inject, vct's; none: opacity only,
// vct_ao), filtered up the tree with the dense chain's kernels.
// Dynamic scenes: the tree is rebuilt from the grid at every `update_every`-th
// update whose grid changed (the article's lower update frequency for dynamic
// geometry); in between the last tree is kept and lit (moved geometry outside
// it is left out: the lag the stats count in frames).
#pragma once
#include <memory>
#include <optional>
#include <string>

#include "illum/resources/cone_volume.h"
#include "voxelize/sparse_octree.h"

namespace vgi {

struct SparseOctreeNeed {
  static constexpr const char* kKind = "sparse_octree";
  static const ResourceKind& row();              // its row of the kinds table (sparseOctreeKind())
  BinaryGridNeed grid;                           // cubic cells
  ConeRadiance radiance = ConeRadiance::Inject;  // inject | texels | none
  bool anisotropic = true;
  bool dilate = true;   // allocate the empty nodes a neighbour's stencil needs (no brick-border artefact)
  int updateEvery = 1;  // dynamic scenes: rebuild the tree at every k-th changed grid
  std::optional<LightMapNeed> lightMaps;   // inject: the direct light's maps
  float bias = 1.0f, normalOffset = 0.0f;  // inject: the maps' shadow test
  int injectSmall = 27;                    // inject: the triangle-parallel path's largest box, in cells
  nlohmann::json key() const;              // what is allocated and how it is rebuilt
  nlohmann::json settings() const;         // what injection reads
  OrMipPyramidNeed pyramid() const { return {grid}; }
};

class SparseOctree : public Resource, public ConeSource {
 public:
  explicit SparseOctree(const SparseOctreeNeed& need) : need_(need) {}
  bool update(SceneResources& res, const ResourceNeed& need, Profiler& profiler) override;
  bool relight(SceneResources& res, const ResourceNeed& need, Profiler& profiler) override;
  nlohmann::json stats() override;
  void* offer(const std::type_info& t) override {
    return offerOf(t, this, static_cast<ConeSource*>(this), octree_.get());
  }
  void bind(ShaderLibrary& shaders, unsigned program, float step) const override;
  float voxelSize() const override { return voxel_; }
  const SparseVoxelOctree& octree() const { return *octree_; }

 private:
  void fill(SceneResources& res, Profiler& profiler);
  SparseOctreeNeed need_;
  std::string filledFor_;
  std::unique_ptr<SparseVoxelOctree> octree_;
  InjectionSums sums_;  // per leaf (radiance inject, texels)
  float voxel_ = 0.0f;
  int gridChanges_ = 0, lag_ = 0;  // grid changes seen; of them since the tree was built
};

// Binds `octree` for cones.glsl (CONE_SVO) on `program` (in use): the octree and the cone uniforms.
void bindConeOctree(const SparseVoxelOctree& octree, ShaderLibrary& shaders, unsigned program, float step);

ResourceKind sparseOctreeKind();

}  // namespace vgi
