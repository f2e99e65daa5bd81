// OSMesa: Mesa's off-screen renderer. Needs a (1×1) colour buffer to be made
// current; everything else renders into FBOs.
// glad must come before any GL header (include sorting would swap them).
// clang-format off
#include <glad/gl.h>
#include <GL/osmesa.h>
// clang-format on

#include <vector>

#include "core/error.h"
#include "core/gl_context.h"

namespace vgi {

namespace {
void* osmesaLoader(const char* name) { return reinterpret_cast<void*>(OSMesaGetProcAddress(name)); }

class OsmesaContext : public GlContext {
 public:
  explicit OsmesaContext(OSMesaContext c) : context_(c), buffer_(4 * 4) {
    makeCurrent();
    loadGlFunctions(&osmesaLoader, "osmesa");
    finishInit("osmesa");
  }
  ~OsmesaContext() override { OSMesaDestroyContext(context_); }
  void makeCurrent() override {
    if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1))
      fail("OSMesa: OSMesaMakeCurrent failed");
  }

 private:
  OSMesaContext context_;
  std::vector<unsigned char> buffer_;
};
}  // namespace

std::unique_ptr<GlContext> createOsmesaContext() {
  // Key, value pairs.
  // clang-format off
  const int attrs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_PROFILE,
                       OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 4,
                       OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
  // clang-format on
  OSMesaContext ctx = OSMesaCreateContextAttribs(attrs, nullptr);
  if (!ctx) fail("OSMesa: could not create a 4.5 core context (Mesa too old, or OSMesa missing)");
  return std::make_unique<OsmesaContext>(ctx);
}

}  // namespace vgi
