// `nearfield`: near-field GI through the voxel grid (VGI §5.1; see nearfield.cpp).
#pragma once
#include <memory>

#include "illum/framework/method.h"

namespace vgi {
// The registry row: name, description, factory, exact counterpart.
MethodInfo nearFieldMethod();
}  // namespace vgi
