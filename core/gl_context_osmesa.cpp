// OSMesa: Mesa's off-screen renderer. Needs a (1×1) colour buffer to be made
// current; everything else renders into FBOs. libOSMesa is loaded when this
// backend is chosen (dlopen), not linked: a GPU node needs no Mesa (and its
// LLVM), and a binary without it still runs every EGL path.
// glad must come before any GL header (include sorting would swap them).
// clang-format off
#include <glad/gl.h>
#include <GL/osmesa.h>
// clang-format on

#include <dlfcn.h>

#include <type_traits>
#include <vector>

#include "core/error.h"
#include "core/gl_context.h"

namespace vgi {

namespace {

// The OSMesa entry points this backend calls, from the library loaded at run time.
struct OsmesaApi {
  decltype(&OSMesaCreateContextAttribs) createContextAttribs = nullptr;
  decltype(&OSMesaMakeCurrent) makeCurrent = nullptr;
  decltype(&OSMesaDestroyContext) destroyContext = nullptr;
  decltype(&OSMesaGetProcAddress) getProcAddress = nullptr;
};

// Loads libOSMesa once (kept for the process: GL function pointers point into it); throws naming
// what is missing.
const OsmesaApi& osmesa() {
  static const OsmesaApi api = [] {
    void* lib = nullptr;
    for (const char* name : {"libOSMesa.so.8", "libOSMesa.so"})
      if ((lib = dlopen(name, RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE))) break;
    if (!lib)
      fail("OSMesa: libOSMesa.so.8 cannot be loaded (", dlerror(),
           "); install Debian's libosmesa6, or use --gl egl");
    OsmesaApi a;
    auto load = [&](auto& fn, const char* symbol) {
      fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(dlsym(lib, symbol));
      if (!fn) fail("OSMesa: libOSMesa has no ", symbol, " (Mesa older than 17?)");
    };
    load(a.createContextAttribs, "OSMesaCreateContextAttribs");
    load(a.makeCurrent, "OSMesaMakeCurrent");
    load(a.destroyContext, "OSMesaDestroyContext");
    load(a.getProcAddress, "OSMesaGetProcAddress");
    return a;
  }();
  return api;
}

void* osmesaLoader(const char* name) { return reinterpret_cast<void*>(osmesa().getProcAddress(name)); }

class OsmesaContext : public GlContext {
 public:
  explicit OsmesaContext(OSMesaContext c) : context_(c), buffer_(4 * 4) {
    makeCurrent();
    loadGlFunctions(&osmesaLoader, "osmesa");
    finishInit("osmesa");
  }
  ~OsmesaContext() override { osmesa().destroyContext(context_); }
  void makeCurrent() override {
    if (!osmesa().makeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1))
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
  OSMesaContext ctx = osmesa().createContextAttribs(attrs, nullptr);
  if (!ctx) fail("OSMesa: could not create a 4.5 core context (Mesa too old, or OSMesa missing)");
  return std::make_unique<OsmesaContext>(ctx);
}

}  // namespace vgi
