// A voxelization against the exact one: recall (exact cells found), precision
// (set cells that are exact), holes (exact cells missed) and extra cells.
#pragma once
#include <nlohmann/json_fwd.hpp>

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

// The "interior" exact set: cells whose box, shrunk by this much (in cells) on
// every side, still overlaps the surface. Where the surface is locally planar,
// such a cell holds a disk of radius ¼ cell of it, and a texel lattice of
// spacing s covers every disk of radius s/√2: with texel ≤ √2/4 cell (2.83
// texels per voxel, times the atlas stretch), points find every interior cell.
// The closed-box set also holds cells the surface merely grazes, which no
// point sampling finds reliably (docs/BENCHMARKS.md).
constexpr double kInteriorShrink = 0.25;

// Throws unless both grids have the same resolution.
GridComparison compareGrids(const BinaryGrid& test, const BinaryGrid& exact);

}  // namespace vgi
