// Headless OpenGL 4.5 core contexts.
//   egl     EGL device platform on a real (non-software) device, e.g. NVIDIA;
//           otherwise EGL surfaceless (Mesa llvmpipe)
//   osmesa  Mesa's off-screen library (llvmpipe), the last fallback
//   auto    egl, then osmesa
// A KHR_debug callback is installed at creation; errors are counted so tests
// can fail on them. Rendering goes to FBOs: no default framebuffer is needed.
#pragma once
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace vgi {

enum class GlBackend { Auto, Egl, Osmesa };
GlBackend parseGlBackend(const std::string& name);  // throws on an unknown name

class GlContext {
 public:
  static std::unique_ptr<GlContext> create(GlBackend backend = GlBackend::Auto);
  virtual ~GlContext() = default;
  virtual void makeCurrent() = 0;

  const std::string& renderer() const { return renderer_; }
  const std::string& version() const { return version_; }
  const std::string& backendName() const { return backend_; }
  bool isSoftware() const;

  // KHR_debug messages of type error or high severity since the last call.
  long errorCount() const;
  std::vector<std::string> takeMessages();

 protected:
  void finishInit(const std::string& backend);  // loads GL, checks 4.5, installs the callback
  static void debugCallback(unsigned source, unsigned type, unsigned id, unsigned severity, int length,
                            const char* message, const void* user);
  std::string renderer_, version_, backend_;
  mutable std::mutex mutex_;
  long errors_ = 0;
  std::vector<std::string> messages_;
};

// Backend-specific constructors (gl_context_egl.cpp, gl_context_osmesa.cpp);
// each throws vgi::Error with the reason when it cannot make a 4.5 core context.
std::unique_ptr<GlContext> createEglContext();
std::unique_ptr<GlContext> createOsmesaContext();

// Resolves GL entry points for the current context's backend.
using GlProcLoader = void* (*)(const char*);
void loadGlFunctions(GlProcLoader loader, const std::string& backend);

}  // namespace vgi
