#include "traverse/brick_tree.h"

#include "core/parallel.h"

namespace vgi {

BrickTree::BrickTree(const OrMipPyramid& pyramid) : grid_(pyramid.words().data()) {
  params_.grid = pyramid.box().params();
  const glm::uvec4 res = params_.grid.resolution;
  params_.levels = shared::brickLevelCount(res);
  uint32_t total = 0;
  for (uint32_t s = 1; s <= params_.levels; ++s) {
    params_.offsets[s] = total;
    total += 2u * shared::bricksPerAxis(res.x, s) * shared::bricksPerAxis(res.y, s) *
             shared::bricksPerAxis(res.z, s);
  }
  words_.assign(total, 0u);
  for (uint32_t s = 1; s <= params_.levels; ++s) {  // each level from the one below
    const uint32_t nx = shared::bricksPerAxis(res.x, s), ny = shared::bricksPerAxis(res.y, s),
                   nz = shared::bricksPerAxis(res.z, s);
    parallelFor(size_t(nz) * ny, 16, 0, [&](size_t b, size_t e) {
      for (size_t zy = b; zy < e; ++zy)
        for (uint32_t x = 0; x < nx; ++x) {
          const uint32_t y = uint32_t(zy % ny), z = uint32_t(zy / ny);
          const glm::uvec2 m = shared::brickNodeMask(params_, s, x, y, z, grid_, words_.data());
          const uint32_t w = shared::brickWordIndex(params_, s, x, y, z, 0u);
          words_[w] = m.x;
          words_[w + 1] = m.y;
        }
    });
  }
}

}  // namespace vgi
