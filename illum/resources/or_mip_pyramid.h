// Resource kind "or_mip_pyramid": the OR-mip pyramid over a binary grid (VGI
// §4: each level the OR of 2×2 columns of the level below, depth kept) that
// the hierarchical, DDA and march tracers read; level 0 is the grid itself.
// GL: a GlPyramid built on the GPU (from the atlas voxelizer's GPU grid or the
// host grid uploaded); CPU: an OrMipPyramid.
#pragma once
#include "illum/resources/binary_grid.h"

namespace vgi {

struct OrMipPyramidNeed {
  static constexpr const char* kKind = "or_mip_pyramid";
  static const ResourceKind& row();  // its row of the kinds table (orMipPyramidKind())
  BinaryGridNeed grid;
  nlohmann::json key() const { return grid.key(); }
};

ResourceKind orMipPyramidKind();

}  // namespace vgi
