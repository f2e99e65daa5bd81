// One render through the same job `vgi render` runs, for the module tests.
#pragma once
#include <string>
#include <vector>

#include "illum/run/render_job.h"

namespace vgi::test {

// A square still of `size` pixels, `spp` samples, quiet.
inline RenderOptions options(const std::string& scene, const std::string& method,
                             std::vector<std::string> set, int size, int spp,
                             std::vector<std::string> aovs = {}) {
  RenderOptions o;
  o.scene = scene;
  o.method = method;
  o.set = std::move(set);
  o.width = o.height = size;
  o.spp = spp;
  o.progress = false;
  o.aovs = std::move(aovs);
  return o;
}

inline RenderOutput render(const std::string& scene, const std::string& method, std::vector<std::string> set,
                           int size, int spp, std::vector<std::string> aovs = {}) {
  return runRender(options(scene, method, std::move(set), size, spp, std::move(aovs)));
}

// The animation of `still`'s options over `frames` frames, `step` apart: each frame's image, and the
// run's output (its stats' "frames": per frame).
struct Frames {
  std::vector<Image> images;
  RenderOutput last;
};
inline Frames renderFrames(const RenderOptions& still, int frames, float step) {
  RenderOptions anim = still;
  anim.frames = frames;
  anim.timeStep = step;
  Frames r;
  r.last = runRender(anim, [&](int, const RenderOutput& out) { r.images.push_back(out.result.image); });
  return r;
}

}  // namespace vgi::test
