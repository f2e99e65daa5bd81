#pragma once
#include <memory>

#include "illum/method.h"

namespace vgi {

// The shadow-map parameters every GL module with direct light reads.
struct ShadowParams {
  int resolution = 1024;
  float bias = 1.0f, normalOffset = 0.0f;
};
void readShadowParams(ParamSet& params, ShadowParams& shadow);

std::unique_ptr<Method> createDirectMethod(ParamSet& params, const Scene& scene);

}  // namespace vgi
