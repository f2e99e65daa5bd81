#include "voxelize/grid_metrics.h"

#include <nlohmann/json.hpp>

#include "core/error.h"

namespace vgi {

nlohmann::json GridComparison::toJson() const {
  return {{"recall", recall()},
          {"precision", precision()},
          {"holes", holes()},
          {"extra", extra()},
          {"exact_voxels", exact}};
}

GridComparison compareGrids(const BinaryGrid& a, const BinaryGrid& e) {
  if (a.box().resolution != e.box().resolution) fail("cannot compare grids of different resolutions");
  GridComparison c;
  const auto &wa = a.words(), &we = e.words();
  for (size_t i = 0; i < wa.size(); ++i) {
    c.set += uint64_t(__builtin_popcount(wa[i]));
    c.exact += uint64_t(__builtin_popcount(we[i]));
    c.found += uint64_t(__builtin_popcount(wa[i] & we[i]));
  }
  return c;
}

}  // namespace vgi
