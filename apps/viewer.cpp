#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>

#include "apps/viewer_impl.h"
#include "core/json_text.h"
#include "core/output_files.h"
#include "core/params.h"
#include "core/progress.h"
#include "illum/framework/resources.h"
#include "illum/run/render_outputs.h"

namespace vgi::app {

namespace fs = std::filesystem;

glm::vec3 turn(glm::vec3 v, glm::vec3 up, float yawDeg, float pitchDeg) {
  up = glm::normalize(up);
  v = glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(yawDeg), up) * glm::vec4(v, 0.0f));
  const glm::vec3 right = glm::normalize(glm::cross(v, up));
  const glm::vec3 p =
      glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(pitchDeg), right) * glm::vec4(v, 0.0f));
  return std::abs(glm::dot(glm::normalize(p), up)) < 0.99f ? p : v;
}

float Viewer::sceneSize() const {
  const Bounds b = job_->scene().bounds(time_);
  return std::max(glm::length(b.hi - b.lo), 1e-6f);
}

void Viewer::restart() {
  // A session still here ends with a view change: the method, its parameters and the scene stand, so
  // the temporal filter's history goes on (a change of those reset the session before).
  viewFrame_ = session_ ? viewFrame_ + 1 : 0;
  session_.reset();
  req_ = job_->request();
  req_.progress = false;
  req_.time = time_;
  req_.temporal = true;
  req_.frame = viewFrame_;
  job_->placeLightsAt(time_);  // lights on a path follow the time (a light moved here has left its path)
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
  Setting back = std::move(*previous_);
  previous_.reset();
  const bool scene = back.job != nullptr;
  if (scene) {  // the scene before: its job as it was
    session_.reset();
    job_ = std::move(back.job);
    home_ = back.home;
    movedLights_ = back.movedLights;
  }
  if (!scene || job_->info().name != back.method || job_->options().set != back.set ||
      job_->options().aovs != back.aovs) {
    attempt("restoring " + back.method, [&] {
      job_->setMethod(back.method, back.set, back.aovs);
      session_.reset();
    });
  }
  const std::string what = scene ? "scene (" + job_->options().scene + ")" : "setting (" + back.method + ")";
  error_ = failed + " (kept the previous " + (scene ? "scene" : "setting") + ")";
  std::fprintf(stderr, "vgi view: kept the previous %s\n", what.c_str());
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

void Viewer::startFromPathCamera() {
  Scene& s = job_->scene();
  s.camera = s.cameraAt(time_);
  s.cameraPath.clear();
  home_ = s.camera;
}

void Viewer::loadScene(const std::string& spec) {
  attempt("scene " + spec, [&] {
    RenderOptions o = job_->options();
    o.scene = spec;
    o.camera.reset();
    o.lightPositions.clear();
    auto job = std::make_unique<RenderJob>(o, gl_.get());
    session_.reset();
    // Until the new scene renders a sample, the old job is kept to come back to (the first one kept
    // stands: two changes before a sample go back to the last scene that rendered).
    if (!previous_ || !previous_->job) {
      rememberSetting();
      previous_->job = std::move(job_);
      previous_->home = home_;
      previous_->movedLights = movedLights_;
    }
    job_ = std::move(job);
    startFromPathCamera();
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
            // While the camera moves each sample is a new frame, filtered with the frames before; when
            // it stands the samples refine that frame, the mean taking over at 1/alpha samples.
            if (session_->addSample()) session_->filter(float(session_->samples()));
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
  startFromPathCamera();
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

int runViewer(const ViewOptions& options) {
  installInterruptHandler();
  Viewer v(options);
  return v.run();
}

}  // namespace vgi::app
