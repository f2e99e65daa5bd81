// `voxels`: a debug view of the binary grid from the camera (see voxel_view.cpp).
#pragma once
#include <memory>

#include "illum/method.h"

namespace vgi {

std::unique_ptr<Method> createVoxelViewMethod(ParamSet& params, const Scene& scene);

}  // namespace vgi
