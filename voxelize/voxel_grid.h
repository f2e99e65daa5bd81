// The voxel grid box and the binary grid (bitmask columns) on the CPU, laid out
// exactly like the GL texture (GL_TEXTURE_2D_ARRAY, RGBA32UI, one layer per
// 128-deep slab) so GPU read-backs compare bit for bit. Conventions:
// shaders/shared/voxel_grid.glsl.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "core/scene.h"
#include "shaders/shared/voxel_grid.glsl"

namespace vgi {

struct GridBox {
  glm::vec3 origin{0.0f};
  glm::mat3 axes{1.0f};  // columns: unit x, y, z axes
  glm::vec3 extent{1.0f};
  glm::uvec3 resolution{128, 128, 128};

  shared::GridParams params() const;
  glm::vec3 voxelSize() const { return extent / glm::vec3(resolution); }
  float voxelDiagonal() const { return glm::length(voxelSize()); }
  uint64_t cellCount() const { return uint64_t(resolution.x) * resolution.y * resolution.z; }
};

// "N" (N×N×N) or "WxHxD"; D must be a multiple of 128 (128 … 1024), W and H in
// 1 … 8192. Throws naming the option and value.
glm::uvec3 parseResolution(const std::string& text, const std::string& option = "--voxels");

// The tight axis-aligned box around the scene at `time`, padded by 1e-5 of its
// size so surfaces on the bounds stay inside under rounding. Flat extents (a
// planar scene) are widened to a sliver so every axis has a positive size.
GridBox fitGridBox(const Scene& scene, glm::uvec3 resolution, float time = 0);
// The same for given bounds (e.g. the union over an animation's frames).
GridBox fitGridBox(Bounds bounds, glm::uvec3 resolution);
// The same box grown about its centre so its cells are cubes (the longest cell side).
GridBox cubicCellBox(const GridBox& box);

// A box of a grid's cells, [lo, hi) per axis.
struct CellRange {
  glm::uvec3 lo{0u}, hi{0u};
  uint64_t count() const {
    const glm::uvec3 s = glm::max(hi, lo) - lo;
    return uint64_t(s.x) * s.y * s.z;
  }
};
// The cells a world-space box covers (its corners through the grid's axes), from `below` cells
// under its lowest cell to `above` − 1 cells over its highest, clamped to the grid; empty
// bounds: an empty range. What moved between two frames (a dynamic mesh's bounds before and
// after) is redone over such a range.
CellRange boundsCells(const GridBox& box, const Bounds& bounds, int below, int above);

// Throws if a grid of this resolution would not fit in memory (names the size).
void checkGridMemory(glm::uvec3 resolution, int grids = 1);

class BinaryGrid {
 public:
  explicit BinaryGrid(const GridBox& box);
  const GridBox& box() const { return box_; }
  uint32_t wordsPerColumn() const { return box_.resolution.z / 32u; }

  // Word w (0 … D/32−1) of column (x, y): slab w/4, component w%4.
  size_t wordIndex(uint32_t x, uint32_t y, uint32_t w) const {
    return shared::columnWordIndex(x, y, w, glm::uvec4(box_.resolution, box_.resolution.z / 128u));
  }
  void set(uint32_t x, uint32_t y, uint32_t z);
  void setAtomic(uint32_t x, uint32_t y, uint32_t z);  // for concurrent writers
  bool test(uint32_t x, uint32_t y, uint32_t z) const;
  uint64_t count() const;
  // FNV-1a over the words: two builds of a grid (two drivers, two voxelizer runs) are the same grid
  // exactly when their digests are (up to 2^-64).
  uint64_t digest() const;
  uint32_t columnCount(uint32_t x, uint32_t y) const;  // set cells in a column

  std::vector<uint32_t>& words() { return words_; }
  const std::vector<uint32_t>& words() const { return words_; }

 private:
  GridBox box_;
  std::vector<uint32_t> words_;
};

// Writes a picture of the grid: left, the number of set cells per column
// (looking along the depth axis); right, the depth of the first set cell.
void writeGridPicture(const BinaryGrid& grid, const std::string& path);

}  // namespace vgi
