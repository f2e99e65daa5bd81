// `voxelpath`: progressive multi-bounce voxel path tracing (VGI §5.2; see voxelpath.cpp).
#pragma once
#include <memory>

#include "illum/method.h"

namespace vgi {

std::unique_ptr<Method> createVoxelPathMethod(ParamSet& params, const Scene& scene);

}  // namespace vgi
