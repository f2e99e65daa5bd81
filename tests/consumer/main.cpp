// Renders the built-in Cornell box with `direct` through the installed
// library and prints what a caller checks: the registry, the shader folder
// it resolved, and the image's mean.
#include <cstdio>
#include <exception>

#include "core/build_info.h"
#include "core/error.h"
#include "core/shader_library.h"
#include "illum/framework/method.h"
#include "illum/run/render_job.h"

int main() {
  try {
    std::printf("vgi %s (%s)\n", vgi::version(), vgi::gitRevision());
    std::printf("shaders %s\n", vgi::defaultShaderDir().c_str());
    for (const vgi::MethodInfo& m : vgi::methodRegistry()) std::printf("method %s\n", m.name.c_str());
    vgi::RenderOptions opt;
    opt.method = "direct";
    opt.methodGiven = true;
    opt.width = opt.height = 32;
    opt.spp = 1;
    opt.progress = false;
    const vgi::RenderOutput out = vgi::runRender(opt);
    double sum = 0;
    for (const auto& p : out.result.image.pixels) sum += p.x + p.y + p.z;
    std::printf("mean %.6f\n", sum / (3.0 * double(out.result.image.pixels.size())));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vgi_consumer: error: %s\n", e.what());
    return 1;
  }
}
