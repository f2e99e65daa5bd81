#pragma once
#include <memory>

#include "illum/method.h"

namespace vgi {
// The near-field radius r as a fraction of the scene's diagonal, when not
// given: the module's and its exact counterpart's (reference integrator=nearfield).
constexpr float kDefaultNearFieldRadius = 0.5f;

std::unique_ptr<Method> createNearFieldMethod(ParamSet& params, const Scene& scene);
}  // namespace vgi
