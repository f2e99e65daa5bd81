// `vct_ao`: ambient occlusion by voxel cone tracing (see vct_ao.cpp).
#pragma once
#include <memory>

#include "illum/method.h"

namespace vgi {

std::unique_ptr<Method> createVctAoMethod(ParamSet& params, const Scene& scene);

}  // namespace vgi
