#include "core/gl_context.h"

#include <glad/gl.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#ifdef VGI_SANITIZE_BUILD
#include <dlfcn.h>

#include <nlohmann/json.hpp>
#endif

#include "core/error.h"

namespace vgi {

GlBackend parseGlBackend(const std::string& name) {
  if (name == "auto") return GlBackend::Auto;
  if (name == "egl") return GlBackend::Egl;
  if (name == "osmesa") return GlBackend::Osmesa;
  if (name == "zink") return GlBackend::Zink;
  fail("--gl: unknown backend '", name, "' (auto, egl, osmesa, zink)");
}

#ifdef VGI_SANITIZE_BUILD
namespace {
// Sanitizer builds only: Mesa unloads its driver at eglTerminate, and the
// allocations it leaks there then have stacks in "<unknown module>", which no
// LeakSanitizer suppression can name. Kept loaded (RTLD_NODELETE), their
// stacks name the driver, and scripts/lsan.supp suppresses exactly Mesa's.
// (libOSMesa is not preloaded: its backend loads it with RTLD_NODELETE itself, and only when chosen.)
void keepMesaLoaded() {
  static const bool once = [] {
    for (const char* lib : {"libEGL_mesa.so.0", "swrast_dri.so",
                            "/usr/lib/x86_64-linux-gnu/dri/swrast_dri.so", "libglapi.so.0"})
      dlopen(lib, RTLD_NOW | RTLD_GLOBAL | RTLD_NODELETE);
    return true;
  }();
  (void)once;
}
// zink likewise: the Vulkan loader unloads lavapipe (the ICD selectZinkOnLavapipe named) at
// vkDestroyInstance, and lavapipe's leaks at exit (two callocs, 112 bytes) then stand in
// "<unknown module>". The ICD's own library_path is kept loaded, so scripts/lsan.supp names it.
void keepVulkanDriverLoaded() {
  static const bool once = [] {
    dlopen("libvulkan.so.1", RTLD_NOW | RTLD_GLOBAL | RTLD_NODELETE);
    const char* icd = std::getenv("VK_ICD_FILENAMES");
    std::ifstream in(icd ? icd : "");
    const nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
    if (j.is_object() && j.contains("ICD") && j["ICD"].value("library_path", "") != "")
      dlopen(j["ICD"]["library_path"].get<std::string>().c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
    return true;
  }();
  (void)once;
}
}  // namespace
#endif

std::unique_ptr<GlContext> GlContext::create(GlBackend backend) {
#ifdef VGI_SANITIZE_BUILD
  keepMesaLoaded();
#endif
  if (backend == GlBackend::Egl) return createEglContext();
  if (backend == GlBackend::Osmesa) return createOsmesaContext();
  if (backend == GlBackend::Zink) {
    selectZinkOnLavapipe();
#ifdef VGI_SANITIZE_BUILD
    keepVulkanDriverLoaded();
#endif
    std::unique_ptr<GlContext> ctx = createEglContext();
    if (ctx->renderer().find("zink") == std::string::npos)
      fail("--gl zink: EGL made a context on '", ctx->renderer(), "', not zink (is Mesa's zink built in?)");
    return ctx;
  }
  std::string eglError;
  try {
    return createEglContext();
  } catch (const Error& e) {
    eglError = e.what();
  }
  try {
    return createOsmesaContext();
  } catch (const Error& e) {
    fail("no OpenGL 4.5 core context could be created.\n  egl: ", eglError, "\n  osmesa: ", e.what());
  }
}

void selectZinkOnLavapipe() {
  const char* icd = std::getenv("VK_ICD_FILENAMES");
  if (icd && *icd) {  // the loader would skip a missing file, and zink fail with no word of why
    std::stringstream list(icd);
    for (std::string f; std::getline(list, f, ':');)
      if (!std::ifstream(f))
        fail("--gl zink: VK_ICD_FILENAMES '", icd, "': '", f,
             "' cannot be read (unset, vgi finds lavapipe's own ICD file)");
  }
  if (!icd || !*icd) {
    static const char* const kIcds[] = {"/usr/share/vulkan/icd.d/lvp_icd.x86_64.json",
                                        "/usr/share/vulkan/icd.d/lvp_icd.json"};
    const char* found = nullptr;
    for (const char* p : kIcds)
      if (std::ifstream(p)) found = p;
    if (!found)
      fail("--gl zink: lavapipe's Vulkan ICD (", kIcds[0],
           ") is missing: install mesa-vulkan-drivers (scripts/setup.sh does), or set VK_ICD_FILENAMES");
    setenv("VK_ICD_FILENAMES", found, 1);
  }
  setenv("GALLIUM_DRIVER", "zink", 1);
  setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1);
  // zink's Wayland/X probes complain without a runtime folder; none is used.
  if (!std::getenv("XDG_RUNTIME_DIR")) setenv("XDG_RUNTIME_DIR", "/tmp", 0);
}

bool GlContext::isSoftware() const {
  return renderer_.find("llvmpipe") != std::string::npos || renderer_.find("softpipe") != std::string::npos ||
         renderer_.find("lavapipe") != std::string::npos;
}

void loadGlFunctions(GlProcLoader loader, const std::string& backend) {
  int v = gladLoadGL(reinterpret_cast<GLADloadfunc>(loader));
  if (!v) fail(backend, ": could not load OpenGL entry points");
  int major = GLAD_VERSION_MAJOR(v), minor = GLAD_VERSION_MINOR(v);
  if (major < 4 || (major == 4 && minor < 5)) {
    const char* ver = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    fail(backend, ": OpenGL 4.5 core is required, but the context offers only ", major, ".", minor,
         " (GL_VERSION '", ver ? ver : "?", "')");
  }
}

namespace {
std::mutex processMutex;
long processErrors = 0;
long processContexts = 0;
std::vector<std::string> processMessages;
}  // namespace

void GlContext::finishInit(const std::string& backend) {
  {
    std::lock_guard<std::mutex> lock(processMutex);
    ++processContexts;
  }
  backend_ = backend;
  renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  version_ = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(reinterpret_cast<GLDEBUGPROC>(&GlContext::debugCallback), this);
  glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
  glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DEBUG_SEVERITY_NOTIFICATION, 0, nullptr, GL_FALSE);
  // The group markers (notifications) tell the callback which pass is running.
  for (GLenum t : {GL_DEBUG_TYPE_PUSH_GROUP, GL_DEBUG_TYPE_POP_GROUP})
    glDebugMessageControl(GL_DEBUG_SOURCE_APPLICATION, t, GL_DONT_CARE, 0, nullptr, GL_TRUE);
}

long GlContext::processErrorCount() {
  std::lock_guard<std::mutex> lock(processMutex);
  return processErrors;
}

long GlContext::processContextCount() {
  std::lock_guard<std::mutex> lock(processMutex);
  return processContexts;
}

std::vector<std::string> GlContext::takeProcessErrors() {
  std::lock_guard<std::mutex> lock(processMutex);
  return std::move(processMessages);
}

void GlContext::debugCallback(unsigned source, unsigned type, unsigned id, unsigned severity, int length,
                              const char* message, const void* user) {
  auto* self = const_cast<GlContext*>(static_cast<const GlContext*>(user));
  // Shader compile errors arrive here too; ShaderLibrary reports those with file
  // and line, so they do not count as API errors.
  bool isError = source != GL_DEBUG_SOURCE_SHADER_COMPILER &&
                 (type == GL_DEBUG_TYPE_ERROR || severity == GL_DEBUG_SEVERITY_HIGH);
  std::string msg(message, length >= 0 ? size_t(length) : std::char_traits<char>::length(message));
  std::lock_guard<std::mutex> lock(self->mutex_);
  if (type == GL_DEBUG_TYPE_PUSH_GROUP) {
    self->groups_.push_back(msg);
    return;
  }
  if (type == GL_DEBUG_TYPE_POP_GROUP) {
    if (!self->groups_.empty()) self->groups_.pop_back();
    return;
  }
  if (isError) {
    ++self->errors_;
    const std::string where =
        self->groups_.empty() ? "outside a timed pass" : "pass '" + self->groups_.back() + "'";
    const std::string text = where + ": GL error (id " + std::to_string(id) + "): " + msg;
    std::fprintf(stderr, "%s\n", text.c_str());
    std::lock_guard<std::mutex> plock(processMutex);
    ++processErrors;
    if (processMessages.size() < 100) processMessages.push_back(text);
  }
  if (self->messages_.size() < 1000) self->messages_.push_back(msg);
}

long GlContext::errorCount() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return errors_;
}

std::vector<std::string> GlContext::takeMessages() {
  std::lock_guard<std::mutex> lock(mutex_);
  return std::move(messages_);
}

}  // namespace vgi
