#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "apps/viewer_impl.h"
#include "core/params.h"

namespace vgi::app {

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
  // Docked to the window's right edge, its full height (the image fills the rest: draw()).
  ImGui::SetNextWindowPos(ImVec2(float(fw - kPanelWidth), 0), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(float(kPanelWidth), float(fh)), ImGuiCond_Always);
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

}  // namespace vgi::app
