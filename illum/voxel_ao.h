// `voxel_ao`: ambient occlusion through the binary voxel grid (see voxel_ao.cpp).
#pragma once
#include <memory>

#include "illum/method.h"

namespace vgi {

// The AO radius as a fraction of the scene's diagonal, when not given: the
// module's and its exact counterpart's (reference integrator=ao).
constexpr float kDefaultAoRadius = 0.1f;

std::unique_ptr<Method> createVoxelAoMethod(ParamSet& params, const Scene& scene);

}  // namespace vgi
