#pragma once
#include "voxelize/voxelizer.h"

namespace vgi {
// Three-axis conservative voxelization (dominant-axis projection with triangle
// expansion), on the GPU.
BinaryGrid voxelizeConservativeGl(const VoxelizeRequest& request, Profiler& profiler, nlohmann::json& stats);
}  // namespace vgi
