// `vpl`: instant radiosity with voxel visibility (VGI §5.3; see vpl.cpp).
#pragma once
#include <memory>

#include "illum/method.h"

namespace vgi {

std::unique_ptr<Method> createVplMethod(ParamSet& params, const Scene& scene);

}  // namespace vgi
