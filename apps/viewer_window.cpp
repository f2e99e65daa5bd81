#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <dlfcn.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "apps/viewer_impl.h"
#include "core/output_files.h"

namespace vgi::app {

namespace {

std::string glfwMessage;
void onGlfwError(int code, const char* message) {
  glfwMessage = "GLFW error " + std::to_string(code) + ": " + (message ? message : "?");
}

void* glfwLoader(const char* name) { return reinterpret_cast<void*>(glfwGetProcAddress(name)); }

}  // namespace

const std::string& lastGlfwError() { return glfwMessage; }

GlfwContext::GlfwContext(GLFWwindow* window) : window_(window) {
  glfwMakeContextCurrent(window_);
  loadGlFunctions(&glfwLoader, "glfw");
  finishInit("glfw");
}

Viewer::~Viewer() {
  session_.reset();
  prof_.reset();
  job_.reset();
  shownTexture_.reset();
  if (vao_) glDeleteVertexArrays(1, &vao_);
  display_.reset();
  if (imgui_) {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  gl_.reset();
  if (window_) glfwDestroyWindow(window_);
  glfwTerminate();
}

void Viewer::openWindow() {
  // GLX loads Mesa's DRI driver and ImGui's GL loader loads glvnd's libGL, and both unload them
  // at shutdown; kept loaded, what Mesa leaks at exit stays attributed to Mesa (LeakSanitizer's
  // suppressions, scripts/lsan.supp) instead of to an unmapped address.
  for (const char* lib : {"libGL.so.1", "libGLX_mesa.so.0", "/usr/lib/x86_64-linux-gnu/dri/swrast_dri.so"})
    dlopen(lib, RTLD_LAZY | RTLD_NODELETE);
  glfwSetErrorCallback(&onGlfwError);
  if (!glfwInit())
    fail("vgi view needs a display and could not open one (", lastGlfwError(),
         "); on a machine without one run it under Xvfb: xvfb-run -a vgi view …");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  const std::string title = "vgi view: " + opt_.render.scene;
  // The image on the left, scaled to fill an area of its own aspect at least the panel's height,
  // the panel beside it.
  const int areaH = std::max(opt_.render.height, kPanelHeight);
  const int areaW = int(std::lround(double(areaH) * opt_.render.width / opt_.render.height));
  window_ = glfwCreateWindow(areaW + kPanelWidth, areaH, title.c_str(), nullptr, nullptr);
  if (!window_) fail("vgi view: no OpenGL 4.5 core window (", lastGlfwError(), ")");
  gl_ = std::make_unique<GlfwContext>(window_);
  glfwSwapInterval(0);
  display_ = std::make_unique<ShaderLibrary>();
  displayProg_ = display_->program({"apps/view_display.vert.glsl", "apps/view_display.frag.glsl"});
  glCreateVertexArrays(1, &vao_);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini beside the user's files
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  ImGui_ImplOpenGL3_Init("#version 450 core");
  imgui_ = true;
}

Viewer::ImageRect Viewer::imageRect(int fw, int fh) const {
  // The area left of the panel (the panel's width in framebuffer pixels: the window may be scaled).
  int ww = 0, wh = 0;
  glfwGetWindowSize(window_, &ww, &wh);
  const int panel = ww > 0 ? int(std::lround(double(kPanelWidth) * fw / ww)) : kPanelWidth;
  const int aw = std::max(1, fw - panel), ah = std::max(1, fh);
  // The largest rectangle of the image's aspect in it, centred.
  const double scale = std::min(double(aw) / shownW_, double(ah) / shownH_);
  ImageRect r;
  r.width = std::max(1, int(std::lround(shownW_ * scale)));
  r.height = std::max(1, int(std::lround(shownH_ * scale)));
  r.x = (aw - r.width) / 2;
  r.y = (ah - r.height) / 2;
  return r;
}

void Viewer::draw(const Image& shown) {
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(window_, &fw, &fh);
  if (shown.width > 0) {
    if (shown.width != shownW_ || shown.height != shownH_) {
      unsigned t = 0;
      glCreateTextures(GL_TEXTURE_2D, 1, &t);
      shownTexture_ = GlTexture(t);
      glTextureStorage2D(t, 1, GL_RGB32F, shown.width, shown.height);
      glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
      shownW_ = shown.width;
      shownH_ = shown.height;
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(shownTexture_.get(), 0, 0, 0, shown.width, shown.height, GL_RGB, GL_FLOAT,
                        shown.pixels.data());
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, fw, fh);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  if (shownTexture_) {
    const ImageRect r = imageRect(fw, fh);
    glViewport(r.x, r.y, r.width, r.height);
    glUseProgram(displayProg_);
    display_->setUniform(displayProg_, "uExposure", exposure_);
    glBindTextureUnit(0, shownTexture_.get());
    glBindVertexArray(vao_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glViewport(0, 0, fw, fh);
  }
}

// The window as shown (image + panel), read back before the swap; the
// framebuffer holds sRGB-encoded values, decoded so the PNG writer's
// encoding gives them back.
void Viewer::writeWindow(const std::string& path) {
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(window_, &fw, &fh);
  std::vector<float> rgb(size_t(fw) * size_t(fh) * 3);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, fw, fh, GL_RGB, GL_FLOAT, rgb.data());
  Image img;
  img.width = fw;
  img.height = fh;
  img.pixels.resize(size_t(fw) * size_t(fh));
  auto linear = [](float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); };
  for (int y = 0; y < fh; ++y)
    for (int x = 0; x < fw; ++x) {
      const float* p = &rgb[(size_t(fh - 1 - y) * size_t(fw) + size_t(x)) * 3];
      img.pixels[size_t(y) * size_t(fw) + size_t(x)] = {linear(p[0]), linear(p[1]), linear(p[2])};
    }
  writeImage(img, path, 1.0f);
  std::fprintf(stderr, "wrote %s (the window, %dx%d)\n", path.c_str(), fw, fh);
}

}  // namespace vgi::app
