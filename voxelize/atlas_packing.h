#pragma once
#include <glm/glm.hpp>
#include <vector>

namespace vgi {

struct ShelfPacking {
  int width = 0, height = 0;
  std::vector<glm::ivec2> offsets;  // lower-left corner of each rectangle
};

// Shelf packing (rectangles sorted by height, filled left to right in rows of
// a width near sqrt(total area)); every rectangle already includes its gutter.
ShelfPacking packShelves(const std::vector<glm::ivec2>& sizes);

}  // namespace vgi
