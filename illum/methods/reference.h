// `reference`: the exact integrals on the CPU through Embree (see reference.cpp).
#pragma once
#include <memory>

#include "illum/framework/method.h"

namespace vgi {
// The registry row: name, description, factory, exact counterpart.
MethodInfo referenceMethod();
}  // namespace vgi
