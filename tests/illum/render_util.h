// One render through the same job `vgi render` runs, for the module tests.
#pragma once
#include <string>
#include <vector>

#include "illum/run/render_job.h"

namespace vgi::test {

inline RenderOutput render(const std::string& scene, const std::string& method, std::vector<std::string> set,
                           int size, int spp, std::vector<std::string> aovs = {}) {
  RenderOptions o;
  o.scene = scene;
  o.method = method;
  o.set = std::move(set);
  o.width = o.height = size;
  o.spp = spp;
  o.progress = false;
  o.aovs = std::move(aovs);
  return runRender(o);
}

}  // namespace vgi::test
