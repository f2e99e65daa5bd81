#pragma once
#include <memory>

#include "illum/method.h"

namespace vgi {
std::unique_ptr<Method> createNearFieldMethod(ParamSet& params, const Scene& scene);
}
