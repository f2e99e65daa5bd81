// The viewer's parts (apps/viewer.h is its interface): one class, its
// member functions defined by concern —
//   viewer.cpp         the session: method, parameters, scene, camera, lights, script events, the frame loop
//   viewer_window.cpp  the GLFW window and its GL context, drawing the image, window screenshots
//   viewer_panels.cpp  the Dear ImGui panels (timings, parameters, views) and the keyboard and mouse
//   viewer_views.cpp   what is shown (image, AOVs, light maps) and screenshots with their stats
//   viewer_script.cpp  --script files: the events, checked before anything runs
#pragma once
// GLFW after glad, without its own GL header.
#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "apps/viewer.h"
#include "apps/viewer_script.h"
#include "core/error.h"
#include "core/gl_context.h"
#include "core/gl_handles.h"
#include "core/image.h"
#include "core/profiler.h"
#include "core/shader_library.h"
#include "illum/framework/sample_loop.h"
#include "illum/run/render_job.h"

namespace vgi::app {

// A light-map view of the "show" list: "rsm.<channel>" or "shadow_map.distance".
inline bool isLightMapView(const std::string& channel) {
  return channel.rfind("rsm.", 0) == 0 || channel.rfind("shadow_map.", 0) == 0;
}

constexpr int kPanelWidth = 360, kPanelHeight = 720;

// The window's context as the framework's GlContext (debug callback, error count, renderer).
class GlfwContext : public GlContext {
 public:
  explicit GlfwContext(GLFWwindow* window);
  void makeCurrent() override { glfwMakeContextCurrent(window_); }

 private:
  GLFWwindow* window_;
};

// The last GLFW error's text (the window's error callback).
const std::string& lastGlfwError();

// v turned by yaw about `up`, then by pitch about cross(v, up) — unless that
// brings it within ~8° of the pole (then only the yaw).
glm::vec3 turn(glm::vec3 v, glm::vec3 up, float yawDeg, float pitchDeg);

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
  // Where the shown image is drawn in a framebuffer of fw × fh: the largest rectangle of its aspect
  // left of the panel, centred (GL's lower-left origin).
  struct ImageRect {
    int x = 0, y = 0, width = 0, height = 0;
  };
  ImageRect imageRect(int fw, int fh) const;
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
  // resources cannot be built, frame() restores them. A scene change keeps the whole previous job
  // (its scene, camera and moved lights): a scene that loads but cannot be built gives way to it.
  struct Setting {
    std::string method;
    std::vector<std::string> set, aovs;
    std::unique_ptr<RenderJob> job;  // the job before a scene change, else null
    Camera home;
    std::set<int> movedLights;
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
  // The scene's camera becomes its path's camera at the current time, and the home the R key
  // returns to; the viewer's camera is the user's to move (a camera path is not played here).
  void startFromPathCamera();
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
  // The sessions since the last change of method, parameters or scene: each view change (camera,
  // time, a light) starts the next frame of the temporal filter's history (0: no history).
  int viewFrame_ = 0;
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

}  // namespace vgi::app
