#pragma once
#include <memory>

#include "illum/method.h"

namespace vgi {
std::unique_ptr<Method> createDirectMethod(ParamSet& params, const Scene& scene);
}
