// `voxel_ao`: ambient occlusion through the binary voxel grid (see voxel_ao.cpp).
#pragma once
#include <memory>

#include "illum/framework/method.h"

namespace vgi {

// The registry row: name, description, factory, exact counterpart.
MethodInfo voxelAoMethod();

}  // namespace vgi
