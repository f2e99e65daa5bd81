#pragma once
#include "voxelize/voxelizer.h"

namespace vgi {
// Three-axis conservative voxelization (dominant-axis projection with triangle
// expansion), on the GPU.
BinaryGrid voxelizeConservativeGl(const VoxelizeRequest& request, Profiler& profiler, nlohmann::json& stats);
// The hybrid: small triangles triangle-parallel in the geometry shader, the
// others fragment-parallel as above, in one pass (request.hybridCutoff).
BinaryGrid voxelizeHybridGl(const VoxelizeRequest& request, Profiler& profiler, nlohmann::json& stats);
}  // namespace vgi
