// The OR-mip pyramid of a binary grid (VGI §4, after Forest et al. 2009 without
// the octree): built on the CPU here or on the GPU (GlPyramid) from the same index kernel
// (shaders/shared/or_mip.glsl), so both produce the same words.
#pragma once
#include <vector>

#include "voxelize/voxel_grid.h"

namespace vgi {

class OrMipPyramid {
 public:
  explicit OrMipPyramid(const BinaryGrid& grid);  // CPU build
  // Adopts words built elsewhere (the GPU); throws if the size does not match.
  OrMipPyramid(const GridBox& box, std::vector<uint32_t> words);

  const GridBox& box() const { return box_; }
  uint32_t levels() const { return uint32_t(offsets_.size()); }
  glm::uvec2 levelSize(uint32_t level) const;
  uint32_t levelOffset(uint32_t level) const { return offsets_[level]; }
  uint32_t depth() const { return box_.resolution.z; }
  bool test(uint32_t level, uint32_t x, uint32_t y, uint32_t z) const;
  const std::vector<uint32_t>& words() const { return words_; }

  // Word offsets of every level for a grid box, and the total word count.
  static std::vector<uint32_t> layout(const GridBox& box, uint32_t& totalWords);

 private:
  GridBox box_;
  std::vector<uint32_t> offsets_;
  std::vector<uint32_t> words_;
};

// The same pyramid is built on the GPU by GlPyramid::build (traverse/gl_ray_tracer.h).

}  // namespace vgi
