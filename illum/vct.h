// `vct`: voxel cone tracing (see vct.cpp).
#pragma once
#include <memory>

#include "illum/method.h"

namespace vgi {

std::unique_ptr<Method> createVctMethod(ParamSet& params, const Scene& scene);

}  // namespace vgi
