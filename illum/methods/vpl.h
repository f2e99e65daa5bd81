// `vpl`: instant radiosity with voxel visibility (VGI §5.3; see vpl.cpp).
#pragma once
#include <memory>

#include "illum/framework/method.h"

namespace vgi {

// The registry row: name, description, factory, exact counterpart.
MethodInfo vplMethod();

}  // namespace vgi
