// A voxelization against the exact one: recall (exact cells found), precision
// (set cells that are exact), holes (exact cells missed) and extra cells.
#pragma once
#include <nlohmann/json.hpp>

#include "voxelize/voxel_grid.h"

namespace vgi {

struct GridComparison {
  uint64_t exact = 0, found = 0, set = 0;  // |E|, |A ∩ E|, |A|
  double recall() const { return exact ? double(found) / double(exact) : 1.0; }
  double precision() const { return set ? double(found) / double(set) : 1.0; }
  uint64_t holes() const { return exact - found; }
  uint64_t extra() const { return set - found; }
  nlohmann::json toJson() const;
};

// Throws unless both grids have the same resolution.
GridComparison compareGrids(const BinaryGrid& test, const BinaryGrid& exact);

}  // namespace vgi
