// The sparse voxel octree of voxel cone tracing (Crassin et al., "Interactive
// Indirect Illumination Using Voxel Cone Tracing", 2011 §3; Crassin & Green,
// OpenGL Insights ch. 22, 2012; ../shared/papers/002_…, the 2013 article;
// Dinse 2015, 003_…, ch. 4–5), built on the GPU and filtered like the dense
// volume of voxelize/value_textures.h, so the cone tracer reads either through
// one sampling interface (shaders/illum/vct/cones.glsl, CONE_SVO).
//
// Build (shaders/voxelize/sparse_octree_build.comp): the fragment list is the binary
// grid's occupied cells (one per cell, from any voxelizer's words); per level
// from the root: flag the nodes the fragments fall in, allocate a tile of 8
// children per flagged node (atomic counter), initialise the new tiles (0);
// depth D = ⌈log2⌉ of the grid's longest side (≤ 10: 1024³). The leaves
// (level D) are the cells: a leaf is occupied where a fragment flagged it.
// Values (shaders/voxelize/sparse_octree_filter.comp): the leaves' premultiplied radiance
// from sums per leaf (vct's injection writes them: INJECT_SVO), then per level
// up the tree the dense chain's kernels (boxMean8, or the six faces'
// anisoReduce) over each node's children, then the bricks' borders.
// Bricks: 3×3×3 texels per tile (the 8 children + one texel on the +side from
// the neighbouring tiles; shared/sparse_octree.glsl explains why this is what the dense
// trilinear sample needs). Pools (RGBA16F 3D textures, as the dense chains):
// anisotropic — the leaves' tiles in the iso pool, every other tile in six
// face pools; isotropic — every tile in the iso pool. `dilate` also allocates
// the empty nodes whose bricks a stencil at a filled neighbour needs (VCT-AO
// §6.2's brick-border artefact; shared/sparse_octree.glsl).
#pragma once
#include <glm/glm.hpp>
#include <map>
#include <nlohmann/json_fwd.hpp>
#include <vector>

#include "core/gl_handles.h"
#include "voxelize/voxel_grid.h"

namespace vgi {

class Profiler;
class ShaderLibrary;

// The nodes with children per level (the leaf level: the occupied leaves), as
// sorted packed cells (svoPackCell), those of them that fragments fall in
// (without dilation: all), and the nodes per level (tiles × 8).
struct SvoStructure {
  std::vector<std::vector<uint32_t>> flagged, occupied;
  std::vector<uint64_t> nodes;
};
// The same structure from fragments (leaf cells) on the CPU, by the shared rule
// (svoFlagTarget): what the GPU build must equal.
SvoStructure svoReferenceStructure(const std::vector<glm::uvec3>& fragments, uint32_t depth, bool dilate);
// The octree depth for a grid: ⌈log2⌉ of its longest side; fails naming the
// resolution past 1024 cells.
uint32_t svoDepth(glm::uvec3 resolution);

class SparseVoxelOctree {
 public:
  SparseVoxelOctree(const GridBox& box, bool anisotropic, bool dilate);
  ~SparseVoxelOctree();
  SparseVoxelOctree(const SparseVoxelOctree&) = delete;
  SparseVoxelOctree& operator=(const SparseVoxelOctree&) = delete;

  // The nodes from a binary grid's words (an OR-mip pyramid's level 0 first;
  // "svo_build"), and empty pools for its tiles.
  void build(unsigned gridWords, ShaderLibrary& shaders, Profiler& profiler);
  // The values: the leaves from sums per leaf slot (counts: uint per leaf;
  // sums: 4 uints per leaf, rgb fixed point of radianceMax) or, with
  // counts = 0, the occupied leaves' opacity only ("svo_resolve"); then the
  // filtering up the tree ("svo_filter") and the borders ("svo_borders").
  void resolve(unsigned counts, unsigned sums, float radianceMax, ShaderLibrary& shaders, Profiler& profiler);
  // Binds the node pool and the pools (the iso pool at TEXUNIT_VALUE_RADIANCE,
  // the faces at TEXUNIT_VALUE_ANISO + f) and sets shared/sparse_octree_lookup.glsl's
  // uniforms on `program`.
  void bind(ShaderLibrary& shaders, unsigned program) const;

  const GridBox& box() const { return box_; }
  bool anisotropic() const { return anisotropic_; }
  uint32_t depth() const { return depth_; }
  uint64_t leafCount() const { return nodeCount_ - leafFirst_; }
  uint64_t nodeCount() const { return nodeCount_; }
  uint64_t fragmentCount() const { return fragments_; }
  size_t bytes() const;
  nlohmann::json describe() const;  // depth, fragments, nodes/bricks/bytes per level and in all

  // Read-backs (tests).
  SvoStructure readStructure() const;
  std::vector<uint32_t> readLeafCells() const;  // per leaf slot its packed cell
  // The occupied leaves that no injected sample reached (counts: uint per leaf slot): the holes.
  uint64_t countUnreachedLeaves(unsigned counts) const;
  // Level m's values (face −1: the iso pool; f: face pool f) by packed cell,
  // for every node of the level.
  std::map<uint32_t, glm::vec4> readLevel(uint32_t level, int face) const;

 private:
  struct Pool {
    GlTexture texture;
    glm::uvec3 bricks{0};
    uint32_t base = 0;  // tile t's brick is t − base
  };
  void allocatePools();
  Pool makePool(uint64_t bricks, uint32_t base) const;
  void grow(uint64_t nodes);
  void shrink();
  GridBox box_;
  bool anisotropic_, dilate_;
  uint32_t depth_ = 0;
  uint64_t fragments_ = 0, nodeCount_ = 1, capacity_ = 0, leafFirst_ = 0;
  // Node ranges per level: [levels_[l].first, levels_[l].second) (level 0: the root; then whole tiles).
  std::vector<std::pair<uint64_t, uint64_t>> levels_;
  GlBuffer nodes_, coords_, counter_;
  Pool iso_, faces_[6];
};

}  // namespace vgi
