// `voxelpath`: progressive multi-bounce voxel path tracing (VGI §5.2; see voxelpath.cpp).
#pragma once
#include <memory>

#include "illum/framework/method.h"

namespace vgi {

// The registry row: name, description, factory, exact counterpart.
MethodInfo voxelPathMethod();

}  // namespace vgi
