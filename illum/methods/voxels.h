// `voxels`: a debug view of the binary grid from the camera (see voxels.cpp).
#pragma once
#include <memory>

#include "illum/framework/method.h"

namespace vgi {

// The registry row: name, description, factory, exact counterpart.
MethodInfo voxelViewMethod();

}  // namespace vgi
