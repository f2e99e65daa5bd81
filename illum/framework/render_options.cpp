#include "illum/framework/render_options.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/json_fields.h"

namespace vgi {

void parseSize(const std::string& text, int& w, int& h) {
  auto x = text.find('x');
  // Each side parsed from a string that outlives the check of `end` (a
  // substr() temporary would be destroyed before *end is read).
  auto side = [](const std::string& digits) {
    if (digits.empty() || digits.size() > 9) return -1L;
    char* end = nullptr;
    long v = std::strtol(digits.c_str(), &end, 10);
    return *end ? -1L : v;
  };
  long a = -1, b = -1;
  if (x != std::string::npos) {
    a = side(text.substr(0, x));
    b = side(text.substr(x + 1));
  }
  if (a < 1 || b < 1 || a > 16384 || b > 16384)
    fail("--size '", text, "': expected WxH with 1 <= W, H <= 16384 (e.g. 512x512)");
  w = int(a);
  h = int(b);
}

std::string cameraText(const Camera& c) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g", c.position.x,
                c.position.y, c.position.z, c.target.x, c.target.y, c.target.z, c.up.x, c.up.y, c.up.z,
                c.fovYDeg);
  return buf;
}

Camera parseCamera(const std::string& text) {
  std::vector<float> v;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) {
    char* end = nullptr;
    const float x = std::strtof(item.c_str(), &end);
    if (item.empty() || *end || !std::isfinite(x))
      fail("--camera '", text, "': '", item, "' is not a finite number");
    v.push_back(x);
  }
  if (v.size() != 9 && v.size() != 10)
    fail("--camera '", text, "': expected px,py,pz,tx,ty,tz,ux,uy,uz[,fov_y_deg] (", v.size(),
         " numbers given)");
  Camera c;
  c.position = {v[0], v[1], v[2]};
  c.target = {v[3], v[4], v[5]};
  c.up = {v[6], v[7], v[8]};
  if (v.size() == 10) c.fovYDeg = v[9];
  if (glm::length(c.target - c.position) < 1e-12f)
    fail("--camera '", text, "': the position and the target coincide");
  if (glm::length(glm::cross(c.target - c.position, c.up)) < 1e-12f * glm::length(c.target - c.position))
    fail("--camera '", text, "': the up vector is parallel to the view direction (or zero)");
  if (!(c.fovYDeg > 0.0f && c.fovYDeg < 180.0f))
    fail("--camera '", text, "': the vertical field of view ", c.fovYDeg, " must be in (0, 180) degrees");
  return c;
}

std::pair<int, glm::vec3> parseLightPosition(const std::string& text) {
  const size_t eq = text.find('=');
  char* end = nullptr;
  const long index = eq == std::string::npos ? -1 : std::strtol(text.c_str(), &end, 10);
  if (eq == std::string::npos || eq == 0 || end != text.c_str() + eq || index < 0 || index > 1000000)
    fail("--light '", text, "': expected I=x,y,z (I: the light's index in the scene, from 0)");
  std::vector<float> v;
  std::stringstream ss(text.substr(eq + 1));
  for (std::string item; std::getline(ss, item, ',');) {
    const float x = std::strtof(item.c_str(), &end);
    if (item.empty() || *end || !std::isfinite(x))
      fail("--light '", text, "': '", item, "' is not a finite number");
    v.push_back(x);
  }
  if (v.size() != 3) fail("--light '", text, "': expected I=x,y,z (", v.size(), " numbers given)");
  return {int(index), glm::vec3(v[0], v[1], v[2])};
}

std::string lightPositionText(int index, glm::vec3 p) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "%d=%.9g,%.9g,%.9g", index, p.x, p.y, p.z);
  return buf;
}

void checkRenderOptions(const RenderOptions& opt) {
  if (opt.spp < 1 || opt.spp > 1 << 20) fail("--spp ", opt.spp, ": must be in [1, 1048576]");
  if (opt.width < 1 || opt.height < 1 || opt.width > 16384 || opt.height > 16384)
    fail("--size ", opt.width, "x", opt.height, ": each side must be in [1, 16384]");
  if (opt.threads < 0 || opt.threads > 1024) fail("--threads ", opt.threads, ": must be in [0, 1024]");
  if (opt.frames < 1 || opt.frames > 100000) fail("--frames ", opt.frames, ": must be in [1, 100000]");
  if (!std::isfinite(opt.time) || !std::isfinite(opt.timeStep))
    fail("--time ", opt.time, " / --time-step ", opt.timeStep, ": must be finite numbers");
  // Each frame's time, as frameTimes() computes it in float, must be finite too.
  const float last = opt.time + float(opt.frames - 1) * opt.timeStep;
  if (!std::isfinite(last))
    fail("--time ", opt.time, " / --time-step ", opt.timeStep, " / --frames ", opt.frames,
         ": the last frame's time (", double(opt.time) + double(opt.frames - 1) * double(opt.timeStep),
         ") is beyond a 32-bit float");
  if (!(opt.timeLimitS >= 0) || !std::isfinite(opt.timeLimitS))
    fail("--time-limit ", opt.timeLimitS, ": must be a finite number of seconds >= 0 (0 = no limit)");
  if (opt.timeLimitS > 0 && opt.frames > 1)
    fail("--time-limit applies to a still; --frames ", opt.frames, " renders an animation");
  if (!opt.checkpoints.empty() && opt.frames > 1)
    fail("--checkpoints applies to a still; --frames ", opt.frames, " renders an animation");
  for (int c : opt.checkpoints)
    if (c < 1 || c > opt.spp)
      fail("--checkpoints: ", c, " is not a sample count in [1, --spp ", opt.spp, "]");
}

namespace {

const char* glBackendText(GlBackend b) {
  switch (b) {
    case GlBackend::Egl:
      return "egl";
    case GlBackend::Osmesa:
      return "osmesa";
    case GlBackend::Zink:
      return "zink";
    case GlBackend::Auto:
      break;
  }
  return "auto";
}

std::string numberText(double v) {
  char t[32];
  std::snprintf(t, sizeof t, "%.9g", v);
  return t;
}

std::string joined(const std::vector<std::string>& items) {
  std::string s;
  for (const std::string& i : items) s += (s.empty() ? "" : ",") + i;
  return s;
}

}  // namespace

std::string shellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::vector<std::string> renderArgs(const RenderOptions& o) {
  const RenderOptions d;
  std::vector<std::string> a;
  auto add = [&a](const char* flag, const std::string& value) { a.insert(a.end(), {flag, value}); };
  if (o.scene != d.scene) add("--scene", o.scene);
  add("--method", o.method);
  for (const std::string& kv : o.set) add("--set", kv);
  if (!o.preset.empty()) add("--preset", o.preset);
  if (o.width != d.width || o.height != d.height)
    add("--size", std::to_string(o.width) + "x" + std::to_string(o.height));
  if (o.spp != d.spp) add("--spp", std::to_string(o.spp));
  if (o.seed != d.seed) add("--seed", std::to_string(o.seed));
  if (o.threads != d.threads) add("--threads", std::to_string(o.threads));
  if (o.time != d.time) add("--time", numberText(o.time));
  if (o.frames != d.frames) add("--frames", std::to_string(o.frames));
  if (o.timeStep != d.timeStep) add("--time-step", numberText(o.timeStep));
  if (o.gl != d.gl) add("--gl", glBackendText(o.gl));
  if (!o.aovs.empty()) add("--aov", joined(o.aovs));
  if (o.accumulation != d.accumulation)
    add("--accumulate", o.accumulation == Accumulation::Plain ? "plain" : "compensated");
  if (!o.checkpoints.empty()) {
    std::vector<std::string> c;
    for (int k : o.checkpoints) c.push_back(std::to_string(k));
    add("--checkpoints", joined(c));
  }
  if (o.timeLimitS > 0) add("--time-limit", numberText(o.timeLimitS));
  if (o.camera) add("--camera", cameraText(*o.camera));
  for (const auto& [i, p] : o.lightPositions) add("--light", lightPositionText(i, p));
  if (!o.progress) a.push_back("--quiet");
  return a;
}

std::string renderCommandLine(const RenderOptions& o) {
  std::string c = "vgi render";
  for (const std::string& a : renderArgs(o)) c += " " + (a.rfind("--", 0) == 0 ? a : shellQuote(a));
  return c;
}

nlohmann::json renderJobJson(const RenderOptions& o) {
  nlohmann::json j;
  j["scene"] = o.scene;
  j["method"] = o.method;
  j["set"] = o.set;
  j["preset"] = o.preset;
  j["width"] = o.width;
  j["height"] = o.height;
  j["spp"] = o.spp;
  j["seed"] = o.seed;
  j["threads"] = o.threads;
  j["time"] = o.time;
  j["frames"] = o.frames;
  j["time_step"] = o.timeStep;
  j["gl"] = glBackendText(o.gl);
  j["aov"] = o.aovs;
  j["accumulate"] = o.accumulation == Accumulation::Plain ? "plain" : "compensated";
  j["checkpoints"] = o.checkpoints;
  j["time_limit"] = o.timeLimitS;
  j["camera"] = o.camera ? nlohmann::json(cameraText(*o.camera)) : nlohmann::json();
  nlohmann::json lights = nlohmann::json::array();
  for (const auto& [i, p] : o.lightPositions) lights.push_back(lightPositionText(i, p));
  j["light"] = lights;
  j["quiet"] = !o.progress;
  return j;
}

RenderOptions readRenderJob(const nlohmann::json& in, const std::string& origin) {
  // A render's stats JSON carries its job under "job".
  const nlohmann::json& j = in.is_object() && in.contains("job") && in["job"].is_object() ? in["job"] : in;
  if (!j.is_object()) fail("job ", origin, ": expected a JSON object (a job, or a render's stats JSON)");
  static const std::set<std::string> keys = {"scene",       "method",     "set",    "preset",  "width",
                                             "height",      "spp",        "seed",   "threads", "time",
                                             "frames",      "time_step",  "gl",     "aov",     "accumulate",
                                             "checkpoints", "time_limit", "camera", "light",   "quiet"};
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!keys.count(it.key())) fail("job ", origin, ": unknown key '", it.key(), "'");
  const JsonFields r(j, "job " + origin);
  RenderOptions o;
  o.scene = r.text("scene", o.scene);
  o.methodGiven = r.has("method");
  o.method = r.text("method", o.method);
  o.set = r.texts("set");
  o.preset = r.text("preset", o.preset);
  o.width = int(r.integer("width", o.width, 1, 16384));
  o.height = int(r.integer("height", o.height, 1, 16384));
  o.spp = int(r.integer("spp", o.spp, 1, 1 << 20));
  o.seed = uint32_t(r.integer("seed", o.seed, 0, 0xffffffffLL));
  o.threads = int(r.integer("threads", o.threads, 0, 1024));
  o.time = float(r.number("time", o.time));
  o.frames = int(r.integer("frames", o.frames, 1, 100000));
  o.timeStep = float(r.number("time_step", o.timeStep));
  const std::string gl = r.text("gl", glBackendText(o.gl));
  if (gl != "auto" && gl != "egl" && gl != "osmesa" && gl != "zink")
    r.bad("gl", "must be auto, egl, osmesa or zink");
  o.gl = parseGlBackend(gl);
  o.aovs = r.texts("aov");
  const std::string acc = r.text("accumulate", "compensated");
  if (acc != "compensated" && acc != "plain") r.bad("accumulate", "must be compensated or plain");
  o.accumulation = acc == "plain" ? Accumulation::Plain : Accumulation::Compensated;
  if (r.has("checkpoints")) {
    if (!j["checkpoints"].is_array()) r.bad("checkpoints", "must be a list of sample counts");
    for (const nlohmann::json& v : j["checkpoints"]) {
      if (!v.is_number_integer() || v.get<long long>() < 1 || v.get<long long>() > (1 << 20))
        r.bad("checkpoints", "must be a list of sample counts");
      o.checkpoints.push_back(v.get<int>());
    }
  }
  o.timeLimitS = r.number("time_limit", o.timeLimitS);
  o.progress = !r.flag("quiet", !o.progress);
  // The option parsers' messages name the flag; say which file it came from.
  try {
    if (r.has("camera")) o.camera = parseCamera(r.text("camera", ""));
    for (const std::string& l : r.texts("light")) o.lightPositions.push_back(parseLightPosition(l));
    checkRenderOptions(o);
  } catch (const Error& e) {
    fail("job ", origin, ": ", e.what());
  }
  return o;
}

}  // namespace vgi
