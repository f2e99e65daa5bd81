// Headless OpenGL 4.5 core contexts.
//   egl     EGL device platform on a real (non-software) device, e.g. NVIDIA;
//           otherwise EGL surfaceless (Mesa llvmpipe)
//   osmesa  Mesa's off-screen library (llvmpipe), the last fallback
//   auto    egl, then osmesa
//   zink    Mesa's GL-over-Vulkan driver on lavapipe (CPU), through EGL surfaceless: a second
//           compiler back end and Vulkan's synchronisation rules, the suite's second driver
//           (needs mesa-vulkan-drivers; the same as GALLIUM_DRIVER=zink LIBGL_ALWAYS_SOFTWARE=1
//           with VK_ICD_FILENAMES naming lavapipe's ICD)
// A KHR_debug callback is installed at creation; errors (type error, or high
// severity, from the API, the driver or the shader compiler at run time) are
// counted per context and in the process, each named by the pass it happened
// in (the debug groups Profiler::Scope pushes), so renders refuse to finish on
// one and every GL test fails on one (tests/gl_error_listener.cpp).
// Rendering goes to FBOs: no default framebuffer is needed.
#pragma once
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace vgi {

enum class GlBackend { Auto, Egl, Osmesa, Zink };
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

  // KHR_debug messages of type error or high severity on this context.
  long errorCount() const;
  std::vector<std::string> takeMessages();
  // The same over every context of the process, for a test harness: the count, and the error
  // messages since the last take ("pass 'vpls': GL error (id 1282): …").
  static long processErrorCount();
  static std::vector<std::string> takeProcessErrors();
  // How many contexts the process has made so far (the test harness checks that a test labelled
  // `unit` makes none: tests/gl_error_listener.cpp).
  static long processContextCount();

 protected:
  void finishInit(const std::string& backend);  // loads GL, checks 4.5, installs the callback
  static void debugCallback(unsigned source, unsigned type, unsigned id, unsigned severity, int length,
                            const char* message, const void* user);
  std::string renderer_, version_, backend_;
  mutable std::mutex mutex_;
  long errors_ = 0;
  std::vector<std::string> messages_;
  std::vector<std::string> groups_;  // the open debug groups: the passes, innermost last
};

// Backend-specific constructors (gl_context_egl.cpp, gl_context_osmesa.cpp);
// each throws vgi::Error with the reason when it cannot make a 4.5 core context.
std::unique_ptr<GlContext> createEglContext();
std::unique_ptr<GlContext> createOsmesaContext();
// Points Mesa at zink on lavapipe (the environment above) before the first context is made; throws
// when lavapipe's ICD file is missing. Mesa reads these once per process: call it before any context.
void selectZinkOnLavapipe();

// Resolves GL entry points for the current context's backend.
using GlProcLoader = void* (*)(const char*);
void loadGlFunctions(GlProcLoader loader, const std::string& backend);

}  // namespace vgi
