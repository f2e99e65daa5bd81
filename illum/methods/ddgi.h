// `ddgi`: irradiance probes with ray-traced visibility (Majercik et al. 2019; see ddgi.cpp).
#pragma once
#include <memory>

#include "illum/framework/method.h"

namespace vgi {
// The registry row: name, description, factory, exact counterpart.
MethodInfo ddgiMethod();
}  // namespace vgi
