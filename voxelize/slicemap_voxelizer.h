#pragma once
#include "voxelize/voxelizer.h"

namespace vgi {
// Single-pass slicemap voxelization (Eisemann & Décoret 2006), on the GPU.
BinaryGrid voxelizeSlicemapGl(const VoxelizeRequest& request, Profiler& profiler, nlohmann::json& stats);
}  // namespace vgi
