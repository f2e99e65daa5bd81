// `vct`: voxel cone tracing (see vct.cpp).
#pragma once
#include <memory>

#include "illum/framework/method.h"

namespace vgi {

// The registry row: name, description, factory, exact counterpart.
MethodInfo vctMethod();

}  // namespace vgi
