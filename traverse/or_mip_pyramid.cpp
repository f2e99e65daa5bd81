// OR-mip pyramid with depth-preserving OR reduction — Thiedemann et al.,
// "Voxel-based Global Illumination", I3D 2011, §4: "each new node is generated
// with a logical OR operation of the child nodes' bitmasks. This way, the
// resolution of the depth stays the same at each level." Non-power-of-two
// grids halve rounding up; a parent on the odd edge ORs only its existing
// children.
#include "traverse/or_mip_pyramid.h"

#include "core/error.h"
#include "shaders/shared/or_mip.glsl"

namespace vgi {

std::vector<uint32_t> OrMipPyramid::layout(const GridBox& box, uint32_t& total) {
  std::vector<uint32_t> offsets;
  const glm::uvec2 base(box.resolution.x, box.resolution.y);
  const uint32_t wordsPerColumn = box.resolution.z / 32u;
  total = 0;
  for (uint32_t l = 0;; ++l) {
    glm::uvec2 s = shared::mipLevelSize(base, l);
    offsets.push_back(total);
    total += s.x * s.y * wordsPerColumn;
    if (s.x == 1u && s.y == 1u) break;
  }
  return offsets;
}

glm::uvec2 OrMipPyramid::levelSize(uint32_t level) const {
  return shared::mipLevelSize(glm::uvec2(box_.resolution.x, box_.resolution.y), level);
}

bool OrMipPyramid::test(uint32_t level, uint32_t x, uint32_t y, uint32_t z) const {
  glm::uvec2 s = levelSize(level);
  return (words_[shared::mipWordIndex(x, y, shared::depthWord(z), s, depth(), offsets_[level])] &
          shared::depthBit(z)) != 0u;
}

OrMipPyramid::OrMipPyramid(const GridBox& box, std::vector<uint32_t> words) : box_(box) {
  uint32_t total = 0;
  offsets_ = layout(box, total);
  if (words.size() != total) fail("OR-mip pyramid: ", words.size(), " words given, ", total, " expected");
  words_ = std::move(words);
}

OrMipPyramid::OrMipPyramid(const BinaryGrid& grid) : box_(grid.box()) {
  uint32_t total = 0;
  offsets_ = layout(box_, total);
  words_.assign(total, 0u);
  std::copy(grid.words().begin(), grid.words().end(), words_.begin());
  const uint32_t D = depth(), wpc = D / 32u;
  for (uint32_t l = 1; l < levels(); ++l) {
    const glm::uvec2 s = levelSize(l), c = levelSize(l - 1);
    for (uint32_t y = 0; y < s.y; ++y)
      for (uint32_t x = 0; x < s.x; ++x)
        for (uint32_t w = 0; w < wpc; ++w) {
          uint32_t r = 0;
          for (uint32_t dy = 0; dy < 2; ++dy)
            for (uint32_t dx = 0; dx < 2; ++dx)
              if (2 * x + dx < c.x && 2 * y + dy < c.y)
                r |= words_[shared::mipWordIndex(2 * x + dx, 2 * y + dy, w, c, D, offsets_[l - 1])];
          words_[shared::mipWordIndex(x, y, w, s, D, offsets_[l])] = r;
        }
  }
}

}  // namespace vgi
