// `direct`: GL deferred direct light with shadow maps (see direct.cpp).
#pragma once
#include <memory>

#include "illum/framework/method.h"

namespace vgi {

// The registry row: name, description, factory, exact counterpart.
MethodInfo directMethod();

}  // namespace vgi
