#pragma once
#include <vector>

#include "voxelize/voxelizer.h"

namespace vgi {

// Binary atlas voxelization on the GPU (VGI §3). Fills stats with "points",
// "atlas_resolution" (largest), "atlases" (per mesh), "triangles_without_texels".
// atlasPoints, if given, receives every mesh's atlas position texture (xyz, w =
// valid), so tests can run the CPU insertion on exactly the same points.
BinaryGrid voxelizeAtlasGl(const VoxelizeRequest& request, Profiler& profiler, nlohmann::json& stats,
                           std::vector<std::vector<glm::vec4>>* atlasPoints = nullptr);

// The insertion step on the CPU, through the same kernel (shared::pointBit).
void insertAtlasPoints(const std::vector<glm::vec4>& positions, BinaryGrid& grid);

}  // namespace vgi
