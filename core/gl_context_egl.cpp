// EGL: the device platform (EGL_EXT_platform_device) on a hardware device, else
// Mesa's surfaceless platform. Contexts are made current without a surface
// (EGL_KHR_surfaceless_context).
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <glad/gl.h>

#include <cstring>

#include "core/error.h"
#include "core/gl_context.h"

namespace vgi {

namespace {

bool hasExtension(const char* list, const char* name) {
  if (!list) return false;
  size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)); p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

void* eglLoader(const char* name) { return reinterpret_cast<void*>(eglGetProcAddress(name)); }

class EglContext : public GlContext {
 public:
  EglContext(EGLDisplay d, EGLContext c, const std::string& backend) : display_(d), context_(c) {
    makeCurrent();
    loadGlFunctions(&eglLoader, backend);
    finishInit(backend);
  }
  ~EglContext() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }
  void makeCurrent() override {
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
      fail("EGL: eglMakeCurrent failed (0x", std::hex, eglGetError(), ")");
  }

 private:
  EGLDisplay display_;
  EGLContext context_;
};

// Creates a 4.5 core debug context on an initialised display, or explains why not.
EGLContext createContext(EGLDisplay dpy, std::string& why) {
  if (!eglBindAPI(EGL_OPENGL_API)) {
    why = "eglBindAPI(EGL_OPENGL_API) failed";
    return EGL_NO_CONTEXT;
  }
  EGLConfig config = nullptr;
  const char* ext = eglQueryString(dpy, EGL_EXTENSIONS);
  if (!hasExtension(ext, "EGL_KHR_no_config_context")) {
    const EGLint attrs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLint n = 0;
    if (!eglChooseConfig(dpy, attrs, &config, 1, &n) || n < 1) {
      why = "no EGL config with EGL_OPENGL_BIT";
      return EGL_NO_CONTEXT;
    }
  }
  if (!hasExtension(ext, "EGL_KHR_surfaceless_context")) {
    why = "EGL_KHR_surfaceless_context is not supported";
    return EGL_NO_CONTEXT;
  }
  const EGLint ctxAttrs[] = {EGL_CONTEXT_MAJOR_VERSION,
                             4,
                             EGL_CONTEXT_MINOR_VERSION,
                             5,
                             EGL_CONTEXT_OPENGL_PROFILE_MASK,
                             EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                             EGL_CONTEXT_OPENGL_DEBUG,
                             EGL_TRUE,
                             EGL_NONE};
  EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, ctxAttrs);
  if (ctx == EGL_NO_CONTEXT) {
    char buf[128];
    std::snprintf(buf, sizeof buf,
                  "eglCreateContext(4.5 core) failed (EGL error 0x%x): the driver may not offer OpenGL 4.5",
                  eglGetError());
    why = buf;
  }
  return ctx;
}

}  // namespace

std::unique_ptr<GlContext> createEglContext() {
  const char* clientExt = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto getPlatformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!getPlatformDisplay) fail("EGL: eglGetPlatformDisplayEXT is not available");
  std::string reasons;

  // 1. A hardware device through the device platform.
  if (hasExtension(clientExt, "EGL_EXT_platform_device")) {
    auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto queryDeviceString =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (queryDevices && queryDeviceString && queryDevices(16, devices, &count)) {
      for (EGLint i = 0; i < count; ++i) {
        const char* devExt = queryDeviceString(devices[i], EGL_EXTENSIONS);
        if (hasExtension(devExt, "EGL_MESA_device_software")) continue;  // llvmpipe: use surfaceless
        EGLDisplay dpy = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, nullptr, nullptr)) {
          reasons += " device " + std::to_string(i) + ": eglInitialize failed;";
          continue;
        }
        std::string why;
        EGLContext ctx = createContext(dpy, why);
        if (ctx != EGL_NO_CONTEXT) return std::make_unique<EglContext>(dpy, ctx, "egl-device");
        reasons += " device " + std::to_string(i) + ": " + why + ";";
        eglTerminate(dpy);
      }
    }
  }

  // 2. Mesa's surfaceless platform (llvmpipe on a machine without a GPU).
  if (hasExtension(clientExt, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay dpy = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (dpy != EGL_NO_DISPLAY && eglInitialize(dpy, nullptr, nullptr)) {
      std::string why;
      EGLContext ctx = createContext(dpy, why);
      if (ctx != EGL_NO_CONTEXT) return std::make_unique<EglContext>(dpy, ctx, "egl-surfaceless");
      reasons += " surfaceless: " + why + ";";
      eglTerminate(dpy);
    } else {
      reasons += " surfaceless: eglInitialize failed;";
    }
  } else {
    reasons += " EGL_MESA_platform_surfaceless is not supported;";
  }
  fail("EGL: no usable display:", reasons.empty() ? " no devices" : reasons);
}

}  // namespace vgi
