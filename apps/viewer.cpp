#include "apps/viewer.h"

#include <glad/gl.h>
// GLFW after glad, without its own GL header.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <dlfcn.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <optional>
#include <set>

#include "core/error.h"
#include "core/gl_context.h"
#include "core/gl_handles.h"
#include "core/image.h"
#include "core/json_text.h"
#include "core/output_files.h"
#include "core/params.h"
#include "core/profiler.h"
#include "core/progress.h"
#include "core/shader_library.h"
#include "illum/framework/resources.h"
#include "illum/framework/sample_loop.h"
#include "illum/resources/light_maps.h"

namespace vgi::app {

namespace fs = std::filesystem;

namespace {

// A light-map view of the "show" list: "rsm.<channel>" or "shadow_map.distance".
bool isLightMapView(const std::string& channel) {
  return channel.rfind("rsm.", 0) == 0 || channel.rfind("shadow_map.", 0) == 0;
}

std::string glfwMessage;
void onGlfwError(int code, const char* message) {
  glfwMessage = "GLFW error " + std::to_string(code) + ": " + (message ? message : "?");
}

constexpr int kPanelWidth = 360, kPanelHeight = 720;

void* glfwLoader(const char* name) { return reinterpret_cast<void*>(glfwGetProcAddress(name)); }

// The window's context as the framework's GlContext (debug callback, error count, renderer).
class GlfwContext : public GlContext {
 public:
  explicit GlfwContext(GLFWwindow* window) : window_(window) {
    glfwMakeContextCurrent(window_);
    loadGlFunctions(&glfwLoader, "glfw");
    finishInit("glfw");
  }
  void makeCurrent() override { glfwMakeContextCurrent(window_); }

 private:
  GLFWwindow* window_;
};

// One event of a --script file.
struct ScriptEvent {
  nlohmann::json value;
  std::string kind;
  size_t index = 0;
};

std::vector<ScriptEvent> loadScript(const std::string& path) {
  const nlohmann::json j = readJsonFile(path, "--script");
  if (!j.is_array()) fail("--script '", path, "': expected a JSON list of events");
  static const std::vector<std::string> kinds = {
      "frames", "orbit",      "move",  "reset_camera",      "method",     "set",  "show",
      "time",   "screenshot", "scene", "window_screenshot", "light_face", "light"};
  std::vector<ScriptEvent> events;
  for (size_t i = 0; i < j.size(); ++i) {
    const std::string where = "--script '" + path + "' event " + std::to_string(i);
    if (!j[i].is_object() || j[i].size() != 1) fail(where, ": expected {\"kind\": value}, not ", j[i].dump());
    const std::string kind = j[i].begin().key();
    const nlohmann::json& v = j[i].begin().value();
    if (std::find(kinds.begin(), kinds.end(), kind) == kinds.end()) {
      std::string list;
      for (auto& k : kinds) list += (list.empty() ? "" : ", ") + k;
      fail(where, ": unknown event '", kind, "' (known: ", list, ")");
    }
    auto numbers = [&](size_t n) {
      if (!v.is_array() || v.size() != n) fail(where, ": '", kind, "' needs ", n, " numbers, not ", v.dump());
      for (auto& x : v)
        if (!x.is_number() || !finiteAsFloat(x.get<double>()))
          fail(where, ": '", kind, "' = ", v.dump(), " has a value that is not a finite 32-bit float");
    };
    if (kind == "frames" && (!v.is_number_integer() || v.get<long>() < 1 || v.get<long>() > 1000000))
      fail(where, ": 'frames' = ", v.dump(), " must be an integer in [1, 1000000]");
    if (kind == "light_face" && (!v.is_number_integer() || v.get<long>() < 0 || v.get<long>() > 1000000))
      fail(where, ": 'light_face' = ", v.dump(), " must be an integer in [0, 1000000]");
    if (kind == "orbit") numbers(2);
    if (kind == "move") numbers(3);
    if ((kind == "method" || kind == "show" || kind == "screenshot" || kind == "scene" ||
         kind == "window_screenshot" || kind == "light") &&
        !v.is_string())
      fail(where, ": '", kind, "' = ", v.dump(), " must be a string");
    if (kind == "set" && !v.is_object())
      fail(where, ": 'set' = ", v.dump(), " must be an object of parameters");
    if (kind == "set")
      for (auto& [k, x] : v.items()) {
        std::string text;
        if (!paramTextOf(x, text))
          fail(where, ": 'set.", k, "' = ", x.dump(), " must be a number, string or bool");
      }
    if (kind == "time" && (!v.is_number() || !finiteAsFloat(v.get<double>())))
      fail(where, ": 'time' = ", v.dump(), " must be a finite 32-bit float");
    if (kind == "screenshot") checkOutputPath(v.get<std::string>());
    if (kind == "light") {
      try {
        parseLightPosition(v.get<std::string>());
      } catch (const Error& e) {
        fail(where, ": ", e.what());
      }
    }
    if (kind == "window_screenshot") checkOutputFile(v.get<std::string>(), where + " window_screenshot");
    events.push_back({v, kind, i});
  }
  return events;
}

// A JSON scalar as --set text (the script checked the values are scalars).
std::string setText(const nlohmann::json& v) {
  std::string text;
  if (!paramTextOf(v, text)) fail("'", v.dump(), "' is not a number, string or bool");
  return text;
}

// v turned by yaw about `up`, then by pitch about cross(v, up) — unless that
// brings it within ~8° of the pole (then only the yaw).
glm::vec3 turn(glm::vec3 v, glm::vec3 up, float yawDeg, float pitchDeg) {
  up = glm::normalize(up);
  v = glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(yawDeg), up) * glm::vec4(v, 0.0f));
  const glm::vec3 right = glm::normalize(glm::cross(v, up));
  const glm::vec3 p =
      glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(pitchDeg), right) * glm::vec4(v, 0.0f));
  return std::abs(glm::dot(glm::normalize(p), up)) < 0.99f ? p : v;
}

class Viewer {
 public:
  explicit Viewer(const ViewOptions& o) : opt_(o) {}
  ~Viewer();
  int run();

 private:
  void openWindow();
  void restart();
  void frame();
  void draw(const Image& shown);
  void panel();
  void timingsPanel();
  void parameterPanel();
  void handleInput(float dt);
  void apply(const ScriptEvent& e);
  // Runs `f`; an error is shown in the panel and logged, and the viewer goes on.
  // `action`: something the user did (a success clears the last error); per-frame work keeps it.
  template <typename F>
  bool attempt(const std::string& what, F&& f, bool action = true);
  void setParameter(const std::string& key, const std::string& value);
  void switchMethod(const std::string& name);
  // The method and parameters before a change, until the change has rendered a sample: if its
  // resources cannot be built, frame() restores them.
  struct Setting {
    std::string method;
    std::vector<std::string> set, aovs;
  };
  std::optional<Setting> previous_;
  void rememberSetting();
  void restorePreviousSetting();
  void show(const std::string& channel);
  // The light maps' channels the resources hold, as "rsm.<channel>" (reflective
  // shadow maps) or "shadow_map.distance"; empty without light maps.
  std::vector<std::string> lightMapViews() const;
  bool showingLightMap() const { return isLightMapView(channel_); }
  int lightFaces() const;  // of the maps as built; −1 before they are
  Image lightMapImage() const;
  void setLightFace(long face);
  void loadScene(const std::string& spec);
  void screenshot(const std::string& path);
  void writeWindow(const std::string& path);
  void orbit(float yawDeg, float pitchDeg);
  void moveLight(int index, glm::vec3 position);
  void move(glm::vec3 rightUpForward);
  float sceneSize() const;

  ViewOptions opt_;
  GLFWwindow* window_ = nullptr;
  bool imgui_ = false;
  std::unique_ptr<GlfwContext> gl_;
  std::unique_ptr<ShaderLibrary> display_;
  unsigned displayProg_ = 0, vao_ = 0;
  GlTexture shownTexture_;
  int shownW_ = 0, shownH_ = 0;
  std::unique_ptr<RenderJob> job_;
  RenderRequest req_;
  std::unique_ptr<Profiler> prof_;
  std::unique_ptr<SampleSession> session_;
  Camera home_;
  bool dirty_ = true, stalled_ = false, playing_ = false, f12Down_ = false;
  float time_ = 0, exposure_ = 1;
  std::string channel_ = "image", error_, sceneInput_, windowShot_;
  std::set<int> movedLights_;  // lights placed by --light or moved here: the screenshot's command has them
  std::vector<std::string> panelKeys_;  // the parameters the panel lists (the screenshot's stats)
  int shotCount_ = 0, recorded_ = 0, failures_ = 0, lightFace_ = 0;
  double frameMs_ = 0;
  std::vector<std::pair<std::string, double>> lastSetup_;  // the last set-up passes timed
};

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

template <typename F>
bool Viewer::attempt(const std::string& what, F&& f, bool action) {
  try {
    f();
    if (action) error_.clear();
    return true;
  } catch (const std::exception& e) {
    error_ = what + ": " + e.what();
    std::fprintf(stderr, "vgi view: %s\n", error_.c_str());
    ++failures_;
    return false;
  }
}

void Viewer::openWindow() {
  // GLX loads Mesa's DRI driver and ImGui's GL loader loads glvnd's libGL, and both unload them
  // at shutdown; kept loaded, what Mesa leaks at exit stays attributed to Mesa (LeakSanitizer's
  // suppressions, scripts/lsan.supp) instead of to an unmapped address.
  for (const char* lib : {"libGL.so.1", "libGLX_mesa.so.0", "/usr/lib/x86_64-linux-gnu/dri/swrast_dri.so"})
    dlopen(lib, RTLD_LAZY | RTLD_NODELETE);
  glfwSetErrorCallback(&onGlfwError);
  if (!glfwInit())
    fail("vgi view needs a display and could not open one (", glfwMessage,
         "); on a machine without one run it under Xvfb: xvfb-run -a vgi view …");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  const std::string title = "vgi view: " + opt_.render.scene;
  // The image at its size on the left, the panel beside it.
  window_ = glfwCreateWindow(opt_.render.width + kPanelWidth, std::max(opt_.render.height, kPanelHeight),
                             title.c_str(), nullptr, nullptr);
  if (!window_) fail("vgi view: no OpenGL 4.5 core window (", glfwMessage, ")");
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

float Viewer::sceneSize() const {
  const Bounds b = job_->scene().bounds(time_);
  return std::max(glm::length(b.hi - b.lo), 1e-6f);
}

void Viewer::restart() {
  session_.reset();
  req_ = job_->request();
  req_.progress = false;
  req_.time = time_;
  // Headless: exactly --frames samples, as `vgi render --spp N` takes them (the same jitter).
  req_.spp = opt_.frames > 0 ? opt_.frames : opt_.render.spp;
  req_.checkpoints.clear();
  req_.timeLimitS = 0;
  prof_ = std::make_unique<Profiler>(job_->gl() != nullptr);
  session_ = std::make_unique<SampleSession>(job_->method(), req_, job_->resources(), job_->targets(),
                                             job_->shaders(), *prof_);
  dirty_ = false;
  stalled_ = false;
}

void Viewer::rememberSetting() {
  if (!previous_) previous_ = Setting{job_->info().name, job_->options().set, job_->options().aovs};
}

void Viewer::restorePreviousSetting() {
  const std::string failed = error_;
  const Setting back = *previous_;
  previous_.reset();
  attempt("restoring " + back.method, [&] {
    job_->setMethod(back.method, back.set, back.aovs);
    session_.reset();
  });
  error_ = failed + " (kept the previous setting)";
  std::fprintf(stderr, "vgi view: kept the previous setting (%s)\n", back.method.c_str());
  dirty_ = true;
  stalled_ = false;
}

void Viewer::setParameter(const std::string& key, const std::string& value) {
  attempt("parameter " + key + "=" + value, [&] {
    std::vector<std::string> set;
    for (auto& kv : job_->options().set)
      if (kv.substr(0, kv.find('=')) != key) set.push_back(kv);
    set.push_back(key + "=" + value);
    rememberSetting();
    job_->setMethod(job_->info().name, set, job_->options().aovs);
    session_.reset();  // it refers to the method and resources the job replaced
    dirty_ = true;
  });
}

void Viewer::switchMethod(const std::string& name) {
  attempt("method " + name, [&] {
    findMethod(name, "method");
    rememberSetting();
    job_->setMethod(name, {}, {});
    session_.reset();  // it refers to the method and resources the job replaced
    channel_ = "image";
    dirty_ = true;
  });
}

void Viewer::show(const std::string& channel) {
  attempt("show " + channel, [&] {
    if (isLightMapView(channel)) {
      const std::vector<std::string> views = lightMapViews();
      if (std::find(views.begin(), views.end(), channel) == views.end()) {
        std::string list;
        for (auto& v : views) list += (list.empty() ? "" : ", ") + v;
        fail("'", job_->info().name, "' renders ",
             views.empty() ? "no light maps" : "the light maps " + list);
      }
      channel_ = channel;  // the method's light maps as rendered for the last sample: no restart
      return;
    }
    std::vector<std::string> aovs;
    if (channel != "image") aovs.push_back(channel);
    job_->setMethod(job_->info().name, job_->options().set, aovs);
    session_.reset();  // it refers to the method and resources the job replaced
    channel_ = channel;
    dirty_ = true;
  });
}

std::vector<std::string> Viewer::lightMapViews() const {
  std::vector<std::string> views;
  const LightMapNeed* need = job_->resources().needs().find<LightMapNeed>();
  if (!need) return views;
  for (auto& c : LightMaps::channelNames(need->reflective))
    views.push_back((need->reflective ? "rsm." : "shadow_map.") + c);
  return views;
}

int Viewer::lightFaces() const {
  const LightMaps* maps = job_->resources().tryGet<LightMaps>();
  return maps ? maps->faceCount() : -1;
}

void Viewer::setLightFace(long face) {
  attempt("light face " + std::to_string(face), [&] {
    const int faces = lightFaces();
    if (face < 0 || (faces >= 0 && face >= faces))
      fail("face ", face, " out of range: the lights' maps have ", faces, " faces (0 … ", faces - 1, ")");
    lightFace_ = int(face);  // (checked again when the maps are there)
  });
}

// The shown light map, for the eye: radiance as stored; normals as n/2 + 1/2,
// positions over the scene's bounds, distances over the scene diagonal; texels
// no surface covers black. Reduced by a whole factor to fit the image area.
Image Viewer::lightMapImage() const {
  const LightMaps& maps = job_->resources().get<LightMaps>();
  const std::string ch = channel_.substr(channel_.find('.') + 1);
  const int face = lightFace_;
  const Image raw = maps.readFace(face, ch), dist = ch == "distance" ? raw : maps.readFace(face, "distance");
  const Bounds b = job_->scene().bounds(time_);
  const glm::vec3 lo = b.lo, extent = glm::max(b.hi - b.lo, glm::vec3(1e-30f));
  const float diag = sceneSize();
  const int k =
      std::max(1, (raw.width + std::min(req_.width, req_.height) - 1) / std::min(req_.width, req_.height));
  Image out(raw.width / k, raw.height / k);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      glm::vec3 sum(0.0f);
      for (int j = 0; j < k; ++j)
        for (int i = 0; i < k; ++i) {
          const int sx = x * k + i, sy = y * k + j;
          const glm::vec3 v = raw.at(sx, sy);
          if (dist.at(sx, sy).x >= 1e29f) continue;  // nothing there
          if (ch == "distance")
            sum += glm::vec3(v.x / diag);
          else if (ch == "normal")
            sum += 0.5f * v + 0.5f;
          else if (ch == "position")
            sum += (v - lo) / extent;
          else
            sum += v;
        }
      out.at(x, y) = sum / float(k * k);
    }
  return out;
}

void Viewer::loadScene(const std::string& spec) {
  attempt("scene " + spec, [&] {
    RenderOptions o = job_->options();
    o.scene = spec;
    o.camera.reset();
    o.lightPositions.clear();
    auto job = std::make_unique<RenderJob>(o, gl_.get());
    session_.reset();
    job_ = std::move(job);
    home_ = job_->scene().camera;
    movedLights_.clear();
    dirty_ = true;
  });
}

void Viewer::moveLight(int index, glm::vec3 position) {
  attempt("light " + lightPositionText(index, position), [&] {
    placeLight(job_->scene().lights, index, position);
    job_->lightsChanged();  // the light maps and the radiance follow; the grid stays
    movedLights_.insert(index);
    dirty_ = true;
  });
}

void Viewer::orbit(float yawDeg, float pitchDeg) {
  Camera& c = job_->scene().camera;
  c.position = c.target + turn(c.position - c.target, c.up, yawDeg, -pitchDeg);
  dirty_ = true;
}

void Viewer::move(glm::vec3 v) {
  Camera& c = job_->scene().camera;
  const glm::vec3 forward = glm::normalize(c.target - c.position);
  const glm::vec3 right = glm::normalize(glm::cross(forward, c.up)), up = glm::cross(right, forward);
  const glm::vec3 delta = (v.x * right + v.y * up + v.z * forward) * sceneSize();
  c.position += delta;
  c.target += delta;
  dirty_ = true;
}

void Viewer::screenshot(const std::string& path) {
  attempt("screenshot " + path, [&] {
    if (!session_ || session_->samples() == 0) fail("nothing rendered yet");
    checkOutputPath(path);
    job_->checkGl();
    prof_->resolve(true);
    RenderOutput out;
    out.result = session_->sofar();
    job_->checkFiniteResult(out.result);
    out.stats = job_->describe();
    out.stats.update(renderStats(out.result, *prof_));
    out.stats["spp"] = session_->samples();
    out.stats["time"] = time_;
    if (showingLightMap()) out.result.aovs[channel_] = lightMapImage();  // what is shown, beside the image
    out.stats["viewer"] = {{"shown", channel_},
                           {"exposure", exposure_},
                           {"panel_parameters", panelKeys_},
                           {"gl_errors", gl_->errorCount()},
                           {"errors_reported", failures_},
                           {"resources_kept", job_->resources().adopted()}};
    if (showingLightMap()) out.stats["viewer"]["light_face"] = lightFace_;
    // The job (and the `vgi render` command) that renders this image again.
    RenderOptions shot = job_->options();
    shot.method = job_->info().name;
    shot.methodGiven = true;
    shot.width = req_.width;
    shot.height = req_.height;
    shot.spp = session_->samples();
    shot.seed = req_.seed;
    shot.time = time_;
    shot.frames = 1;
    shot.progress = true;
    shot.camera = job_->scene().camera;
    shot.lightPositions.clear();
    for (int i : movedLights_) shot.lightPositions.emplace_back(i, job_->scene().lights[size_t(i)].position);
    out.stats["job"] = renderJobJson(shot);
    out.stats["command"] = renderCommandLine(shot);
    for (auto& f : writeRenderOutputs(out, path, exposure_)) std::fprintf(stderr, "wrote %s\n", f.c_str());
    ++shotCount_;
  });
}

void Viewer::apply(const ScriptEvent& e) {
  const nlohmann::json& v = e.value;
  if (e.kind == "frames") {
    for (long i = 0; i < v.get<long>() && !glfwWindowShouldClose(window_) && !interruptRequested(); ++i)
      frame();
  } else if (e.kind == "orbit") {
    orbit(v[0].get<float>(), v[1].get<float>());
  } else if (e.kind == "move") {
    move({v[0].get<float>(), v[1].get<float>(), v[2].get<float>()});
  } else if (e.kind == "reset_camera") {
    job_->scene().camera = home_;
    dirty_ = true;
  } else if (e.kind == "method") {
    switchMethod(v.get<std::string>());
  } else if (e.kind == "set") {
    for (auto& [k, x] : v.items()) setParameter(k, setText(x));
  } else if (e.kind == "show") {
    show(v.get<std::string>());
  } else if (e.kind == "time") {
    time_ = v.get<float>();
    dirty_ = true;
  } else if (e.kind == "screenshot") {
    screenshot(v.get<std::string>());
  } else if (e.kind == "scene") {
    loadScene(v.get<std::string>());
  } else if (e.kind == "light") {
    const auto [index, position] = parseLightPosition(v.get<std::string>());
    moveLight(index, position);
  } else if (e.kind == "light_face") {
    setLightFace(v.get<long>());
  } else if (e.kind == "window_screenshot") {
    windowShot_ = v.get<std::string>();
    frame();  // the next frame is read back from the window, panel included
  }
}

void Viewer::handleInput(float dt) {
  const ImGuiIO& io = ImGui::GetIO();
  if (!io.WantCaptureKeyboard) {
    glm::vec3 v(0.0f);
    auto key = [&](int k) { return glfwGetKey(window_, k) == GLFW_PRESS ? 1.0f : 0.0f; };
    v.x = key(GLFW_KEY_D) - key(GLFW_KEY_A);
    v.y = key(GLFW_KEY_E) - key(GLFW_KEY_Q);
    v.z = key(GLFW_KEY_W) - key(GLFW_KEY_S);
    const float speed = (key(GLFW_KEY_LEFT_SHIFT) > 0 ? 1.0f : 0.2f) * dt;  // scene diagonals per second
    if (v != glm::vec3(0.0f)) move(v * speed);
    if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) glfwSetWindowShouldClose(window_, 1);
    if (glfwGetKey(window_, GLFW_KEY_R) == GLFW_PRESS) {
      job_->scene().camera = home_;
      dirty_ = true;
    }
    const bool f12 = glfwGetKey(window_, GLFW_KEY_F12) == GLFW_PRESS;
    if (f12 && !f12Down_) {  // one shot per key press
      char name[64];
      std::snprintf(name, sizeof name, "vgi_view_%03d.exr", shotCount_);
      screenshot(name);
    }
    f12Down_ = f12;
  }
  if (!io.WantCaptureMouse) {
    const ImVec2 d = io.MouseDelta;
    if (io.MouseDown[0] && (d.x != 0 || d.y != 0)) orbit(-0.3f * d.x, -0.3f * d.y);
    if (io.MouseDown[1] && (d.x != 0 || d.y != 0)) {  // look around (fly)
      Camera& c = job_->scene().camera;
      c.target = c.position + turn(c.target - c.position, c.up, -0.2f * d.x, -0.2f * d.y);
      dirty_ = true;
    }
    if (io.MouseWheel != 0) {
      Camera& c = job_->scene().camera;
      c.position = c.target + (c.position - c.target) * std::pow(0.9f, io.MouseWheel);
      dirty_ = true;
    }
  }
}

void Viewer::timingsPanel() {
  if (!ImGui::CollapsingHeader("Timings", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::Text("frame %.1f ms (%.1f fps), %d samples", frameMs_, frameMs_ > 0 ? 1000.0 / frameMs_ : 0.0,
              session_ ? session_->samples() : 0);
  const nlohmann::json ms = prof_ ? prof_->timingsMs() : nlohmann::json::object();
  const nlohmann::json calls = prof_ ? prof_->callCounts() : nlohmann::json::object();
  // Per pass: the mean time of a call since the accumulation started (GPU timestamps where measured);
  // a pass called once per sample is a per-sample pass, the others are set-up (voxelization, light maps).
  const int samples = session_ ? session_->samples() : 0;
  std::vector<std::pair<std::string, double>> perSample, setup;
  double most = 1e-9, sum = 0;
  for (auto& [name, t] : ms.items()) {
    const long n = std::max(1L, calls.value(name, 1L));
    const double each = t.get<double>() / double(n);
    if (samples > 0 && n >= samples) {  // (the display's read-back too: once per frame here)
      perSample.emplace_back(name, each);
      most = std::max(most, each);
      sum += each;
    } else {
      setup.emplace_back(name, t.get<double>());
    }
  }
  auto bars = [&](const std::vector<std::pair<std::string, double>>& list, double scale) {
    for (auto& [name, t] : list) {
      char label[96];
      std::snprintf(label, sizeof label, "%s %.2f ms", name.c_str(), t);
      ImGui::ProgressBar(float(std::min(1.0, t / scale)), ImVec2(-1.0f, 0.0f), label);
    }
  };
  ImGui::Text("per sample: %.1f ms in %zu passes", sum, perSample.size());
  bars(perSample, most);
  if (setup.empty())
    setup = lastSetup_;  // the resources were built before the last restart
  else
    lastSetup_ = setup;
  if (!setup.empty()) {
    ImGui::Separator();
    ImGui::Text("set-up (once, ms in all)");
    double m = 1e-9;
    for (auto& p : setup) m = std::max(m, p.second);
    bars(setup, m);
  }
}

void Viewer::parameterPanel() {
  if (!ImGui::CollapsingHeader("Parameters", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const nlohmann::json values = job_->params().resolved();
  panelKeys_.clear();
  for (const ParamDoc& d : job_->params().docs()) {
    if (!values.contains(d.key)) continue;  // declared for another configuration
    panelKeys_.push_back(d.key);
    const nlohmann::json& v = values[d.key];
    ImGui::PushID(d.key.c_str());
    if (d.type == "bool") {
      bool b = v.get<bool>();
      if (ImGui::Checkbox(d.key.c_str(), &b)) setParameter(d.key, b ? "true" : "false");
    } else if (d.type == "int") {
      // Typed values apply on Enter (or a +/- step); out of range is reported, the old value stays.
      int x = v.get<int>();
      if (ImGui::InputInt(d.key.c_str(), &x, 1, 16, ImGuiInputTextFlags_EnterReturnsTrue))
        setParameter(d.key, std::to_string(x));
    } else if (d.type == "float") {
      float x = v.get<float>();
      if (ImGui::InputFloat(d.key.c_str(), &x, 0.0f, 0.0f, "%.6g", ImGuiInputTextFlags_EnterReturnsTrue))
        setParameter(d.key, setText(nlohmann::json(x)));
    } else if (!d.allowed.empty()) {
      const std::string cur = v.get<std::string>();
      if (ImGui::BeginCombo(d.key.c_str(), cur.c_str())) {
        for (auto& a : d.allowed)
          if (ImGui::Selectable(a.c_str(), a == cur) && a != cur) setParameter(d.key, a);
        ImGui::EndCombo();
      }
    } else {
      std::string text = v.is_string() ? v.get<std::string>() : v.dump();
      if (ImGui::InputText(d.key.c_str(), &text, ImGuiInputTextFlags_EnterReturnsTrue))
        setParameter(d.key, text);
    }
    if (ImGui::IsItemHovered()) {
      const std::string tip =
          d.doc + (d.type == "int" || d.type == "float"
                       ? " [" + setText(nlohmann::json(d.lo)) + ", " + setText(nlohmann::json(d.hi)) + "]"
                       : "");
      ImGui::SetTooltip("%s", tip.c_str());
    }
    ImGui::PopID();
  }
}

void Viewer::panel() {
  int fw = 0, fh = 0;
  glfwGetWindowSize(window_, &fw, &fh);
  ImGui::SetNextWindowPos(ImVec2(float(opt_.render.width), 0), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(float(kPanelWidth), float(fh)), ImGuiCond_FirstUseEver);
  ImGui::Begin("vgi view");
  ImGui::TextWrapped("%s", job_->options().scene.c_str());
  ImGui::TextWrapped("GL: %s", gl_->renderer().c_str());
  if (!error_.empty()) ImGui::TextColored(ImVec4(1.0f, 0.35f, 0.3f, 1.0f), "%s", error_.c_str());
  if (gl_->errorCount() > 0)
    ImGui::TextColored(ImVec4(1, 0.35f, 0.3f, 1), "GL errors: %ld", gl_->errorCount());
  if (ImGui::BeginCombo("method", job_->info().name.c_str())) {
    for (auto& m : methodRegistry())
      if (ImGui::Selectable(m.name.c_str(), m.name == job_->info().name) && m.name != job_->info().name)
        switchMethod(m.name);
    ImGui::EndCombo();
  }
  if (ImGui::BeginCombo("show", channel_.c_str())) {
    std::vector<std::string> outs = {"image"};
    for (auto& o : job_->method().outputs()) outs.push_back(o);
    for (auto& o : lightMapViews()) outs.push_back(o);
    for (auto& o : outs)
      if (ImGui::Selectable(o.c_str(), o == channel_) && o != channel_) show(o);
    ImGui::EndCombo();
  }
  if (showingLightMap() && lightFaces() > 0) {
    int face = lightFace_;
    if (ImGui::SliderInt("light face", &face, 0, lightFaces() - 1)) setLightFace(face);
  }
  ImGui::SliderFloat("exposure", &exposure_, 0.05f, 20.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
  if (job_->scene().hasDynamicMeshes()) {
    ImGui::Checkbox("play", &playing_);
    ImGui::SameLine();
    if (ImGui::SliderFloat("time", &time_, 0.0f, 10.0f)) dirty_ = true;
  }
  if (ImGui::Button("reset camera (R)")) {
    job_->scene().camera = home_;
    dirty_ = true;
  }
  ImGui::SameLine();
  if (ImGui::Button("screenshot (F12)")) {
    char name[64];
    std::snprintf(name, sizeof name, "vgi_view_%03d.exr", shotCount_);
    screenshot(name);
  }
  if (sceneInput_.empty()) sceneInput_ = job_->options().scene;
  if (ImGui::InputText("scene", &sceneInput_, ImGuiInputTextFlags_EnterReturnsTrue)) loadScene(sceneInput_);
  if (!job_->scene().lights.empty() && ImGui::CollapsingHeader("Lights")) {
    for (size_t i = 0; i < job_->scene().lights.size(); ++i) {
      const Light& l = job_->scene().lights[i];
      if (l.type == LightType::Directional) continue;
      glm::vec3 p = l.position;
      ImGui::PushID(int(i));
      ImGui::DragFloat3((std::string(lightTypeName(l.type)) + " " + std::to_string(i)).c_str(), &p.x,
                        0.005f * sceneSize());
      if (ImGui::IsItemDeactivatedAfterEdit()) moveLight(int(i), p);
      ImGui::PopID();
    }
  }
  timingsPanel();
  parameterPanel();
  ImGui::End();
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
      glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
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
    glViewport(0, fh - shownH_, shownW_, shownH_);  // top left, one texel per pixel
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

void Viewer::frame() {
  const auto t0 = std::chrono::steady_clock::now();
  glfwPollEvents();
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  const bool interactive = opt_.frames == 0 && opt_.script.empty();
  if (interactive) handleInput(float(frameMs_ / 1000.0));
  if (playing_) {
    time_ += float(frameMs_ / 1000.0);
    if (time_ > 10.0f) time_ = 0.0f;
    dirty_ = true;
  }
  panel();
  // A change whose resources cannot be built (a grid the atlas cannot fit, a light map beyond the
  // device) falls back to the setting before it, which renders in the same frame.
  for (int attemptNo = 0; attemptNo < 2; ++attemptNo) {
    bool failed = dirty_ && !attempt(
                                "render", [&] { restart(); }, false);
    if (!failed && !stalled_ && session_ && session_->samples() < req_.spp) {
      failed = !attempt(
          "render",
          [&] {
            session_->addSample();
            prof_->resolve(false);
          },
          false);
      if (!failed) previous_.reset();  // the change stands
    }
    if (!failed) break;
    if (!previous_) {
      stalled_ = true;  // until something changes
      break;
    }
    restorePreviousSetting();
  }
  Image shown;
  if (showingLightMap() && lightMapViews().empty()) channel_ = "image";  // another scene or method
  if (session_ && session_->samples() > 0) {
    if (showingLightMap() && lightFace_ >= lightFaces())  // a face set before the maps were built
      attempt("light face " + std::to_string(lightFace_), [&] {
        const int n = lightFaces();
        lightFace_ = 0;
        fail("out of range: the lights' maps have ", n, " faces (0 … ", n - 1, "); showing face 0");
      });
    attempt(
        "read", [&] { shown = showingLightMap() ? lightMapImage() : session_->read(channel_); }, false);
  }
  draw(shown);
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  if (!windowShot_.empty()) {
    attempt("window screenshot " + windowShot_, [&] { writeWindow(windowShot_); });
    windowShot_.clear();
  }
  glfwSwapBuffers(window_);
  if (!opt_.record.empty() && shown.width > 0) {
    char name[32];
    std::snprintf(name, sizeof name, "/frame_%05d.png", recorded_++);
    writeImage(shown, opt_.record + name, exposure_);
  }
  frameMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

int Viewer::run() {
  std::vector<ScriptEvent> script;
  if (!opt_.script.empty()) script = loadScript(opt_.script);  // checked before the window opens
  if (!opt_.screenshot.empty()) checkOutputPath(opt_.screenshot);
  if (!opt_.record.empty()) {
    std::error_code ec;
    fs::create_directories(opt_.record, ec);
    if (ec || !fs::is_directory(opt_.record)) fail("--record '", opt_.record, "' cannot be made a folder");
  }
  exposure_ = opt_.exposure;
  time_ = opt_.render.time;
  openWindow();
  const bool headless = opt_.frames > 0 || !opt_.script.empty();
  try {
    job_ = std::make_unique<RenderJob>(opt_.render, gl_.get());
  } catch (const Error& e) {
    if (headless) throw;
    // Interactive: the window stays and shows why; the built-in Cornell box stands in.
    error_ = std::string(e.what()) + " (showing builtin:cornell)";
    std::fprintf(stderr, "vgi view: %s\n", error_.c_str());
    RenderOptions o = opt_.render;
    o.scene = "builtin:cornell";
    o.method = defaultMethodName();
    o.set.clear();
    o.preset.clear();
    o.camera.reset();
    job_ = std::make_unique<RenderJob>(o, gl_.get());
    const std::string keep = error_;
    frame();
    error_ = keep;
  }
  home_ = job_->scene().camera;
  for (auto& l : job_->options().lightPositions) movedLights_.insert(l.first);
  if (!script.empty()) {
    // Ctrl-C: the events done stand (their screenshots written); the rest is not run.
    for (auto& e : script)
      if (!interruptRequested()) apply(e);
  } else if (opt_.frames > 0) {
    while (!glfwWindowShouldClose(window_) && !interruptRequested() &&
           (!session_ || dirty_ || session_->samples() < opt_.frames)) {
      const int before = session_ ? session_->samples() : -1;
      frame();
      if (stalled_ || (session_ && session_->samples() == before && !dirty_))
        break;  // an error: nothing more
    }
  } else {
    while (!glfwWindowShouldClose(window_) && !interruptRequested()) frame();
  }
  // Interrupted (Ctrl-C): the screenshot of what was accumulated is still written, and the exit is 130.
  const bool interrupted = interruptRequested();
  if (!opt_.screenshot.empty()) {
    const int before = shotCount_;
    screenshot(opt_.screenshot);
    if (shotCount_ == before) return 2;  // nothing to write: the session's error was reported
  }
  std::fprintf(stderr, "vgi view: %d frames recorded, %d screenshots, %d errors reported, %ld GL errors%s\n",
               recorded_, shotCount_, failures_, gl_->errorCount(), interrupted ? ", interrupted" : "");
  if (gl_->errorCount() > 0) return 3;  // a GL error is a bug (the README's scheme)
  return interrupted ? 130 : 0;
}

}  // namespace

int runViewer(const ViewOptions& options) {
  installInterruptHandler();
  Viewer v(options);
  return v.run();
}

}  // namespace vgi::app
