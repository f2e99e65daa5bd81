// 4³ bricks over a binary grid (shaders/shared/brick_tree.glsl; issue "Speed on the GL device", step 4):
// the grid's OR taken 4×4×4 cells at a time, one 64-bit mask per node, built on the CPU by the shared
// kernel. Traced by trace_bricks.glsl (the `bricks` tracer of traverse/ray_tracers.h, C++ only so far:
// its counts are measured against the column pyramid's before a GLSL path is written).
#pragma once
#include <cstdint>
#include <vector>

#include "shaders/shared/brick_tree.glsl"
#include "traverse/or_mip_pyramid.h"

namespace vgi {

class BrickTree {
 public:
  // Over level 0 of `pyramid` (the grid), which must outlive this tree.
  explicit BrickTree(const OrMipPyramid& pyramid);
  const shared::BrickTreeParams& params() const { return params_; }
  const uint32_t* gridWords() const { return grid_; }
  const std::vector<uint32_t>& words() const { return words_; }

 private:
  shared::BrickTreeParams params_{};
  const uint32_t* grid_;
  std::vector<uint32_t> words_;
};

}  // namespace vgi
