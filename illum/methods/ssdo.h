// `ssdo`: screen-space directional occlusion with one indirect bounce (Ritschel et al. 2009; see ssdo.cpp).
#pragma once
#include <memory>

#include "illum/framework/method.h"

namespace vgi {
// The registry row: name, description, factory, exact counterpart.
MethodInfo ssdoMethod();
}  // namespace vgi
