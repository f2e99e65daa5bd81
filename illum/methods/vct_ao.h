// `vct_ao`: ambient occlusion by voxel cone tracing (see vct_ao.cpp).
#pragma once
#include <memory>

#include "illum/framework/method.h"

namespace vgi {

// The registry row: name, description, factory, exact counterpart.
MethodInfo vctAoMethod();

}  // namespace vgi
