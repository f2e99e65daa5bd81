#include "core/scene_loader.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>

#include "core/builtin_scenes.h"
#include "core/error.h"
#include "core/image.h"
#include "core/image_io.h"
#include "core/json_text.h"
#include "core/smooth_normals.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace vgi {

// Where a scene's numbers must lie so that every method computes finite
// values with them: coordinates well inside Embree's valid ray range (|x| <
// 1.8e18) and far from float overflow in squared distances; light and
// emitted power such that sums over 10⁶ samples stay finite in float.
constexpr float kMaxCoordinate = 1e12f, kMaxRadiometric = 1e20f;
// Normals generated for meshes without them: smoothed across edges up to this angle; a vertex
// position with more distinct face normals than the bound stays flat (core/smooth_normals.h).
constexpr float kMaxSmoothingAngleDegrees = 60.0f;
constexpr int kMaxDistinctNormalsPerPosition = 1024;

void checkSceneRanges(const Scene& scene, const std::string& origin) {
  auto coordinate = [&](glm::vec3 v, const std::string& what) {
    for (int k = 0; k < 3; ++k)
      if (!(std::abs(v[k]) <= kMaxCoordinate))
        fail(origin, ": ", what, " (", v.x, ", ", v.y, ", ", v.z, ") lies beyond ±", kMaxCoordinate,
             " scene units (coordinates that large lose all precision in float)");
  };
  auto power = [&](glm::vec3 v, const std::string& what) {
    for (int k = 0; k < 3; ++k)
      if (!(v[k] <= kMaxRadiometric))
        fail(origin, ": ", what, " (", v.x, ", ", v.y, ", ", v.z, ") exceeds ", kMaxRadiometric);
  };
  // A cut-away distance at or beyond the scene's farthest point along the view axis leaves nothing
  // to see (and a near plane 1e20 out put Embree's ray origins beyond its range).
  auto cutAway = [&](const Camera& cam, const Bounds& b, const std::string& what) {
    if (!(cam.clipNear > 0.0f)) return;
    const glm::vec3 fwd = glm::normalize(cam.target - cam.position);
    float farthest = 0.0f;
    for (int k = 0; k < 8; ++k) {
      const glm::vec3 corner((k & 1) ? b.hi.x : b.lo.x, (k & 2) ? b.hi.y : b.lo.y, (k & 4) ? b.hi.z : b.lo.z);
      farthest = std::max(farthest, glm::dot(corner - cam.position, fwd));
    }
    if (!(cam.clipNear < farthest))
      fail(origin, ": ", what, " ", cam.clipNear,
           " lies at or beyond the whole scene (its farthest point is ", farthest,
           " along the view axis): the image would be empty");
  };
  Bounds b = scene.bounds();
  coordinate(b.lo, "the geometry's bounding-box corner");
  coordinate(b.hi, "the geometry's bounding-box corner");
  coordinate(scene.camera.position, "camera.position");
  coordinate(scene.camera.target, "camera.target");
  for (size_t k = 0; k < scene.cameraPath.size(); ++k) {
    const std::string where = "camera.keyframes[" + std::to_string(k) + "]";
    coordinate(scene.cameraPath[k].camera.position, where + ".position");
    coordinate(scene.cameraPath[k].camera.target, where + ".target");
    cutAway(scene.cameraPath[k].camera, scene.bounds(scene.cameraPath[k].time), "camera.near at " + where);
  }
  if (scene.cameraPath.empty()) cutAway(scene.camera, b, "camera.near");
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const std::string where = "lights[" + std::to_string(i) + "]";
    coordinate(scene.lights[i].position, where + ".position");
    for (size_t k = 0; k < scene.lights[i].keyframes.size(); ++k)
      coordinate(scene.lights[i].keyframes[k].position,
                 where + ".keyframes[" + std::to_string(k) + "].position");
    power(scene.lights[i].intensity, where + " intensity");
  }
  for (auto& m : scene.materials) power(m.emission, "material '" + m.name + "' emission");
  power(scene.environment.color * scene.environment.scale, "environment colour x scale");
}

namespace {

bool finite3(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string lower(std::string s) {
  for (auto& c : s) c = char(std::tolower(c));
  return s;
}

// albedo + ks > 1 reflects more light than arrives (and breaks the furnace
// test); scale ks down so each channel sums to at most 1, and say so.
void conserveEnergy(Material& m, const std::string& where, LoadReport& report) {
  glm::vec3 sum = m.albedo + m.ks;
  float worst = std::max({sum.x, sum.y, sum.z});
  if (worst <= 1.0f) return;
  glm::vec3 room = glm::max(glm::vec3(1.0f) - m.albedo, glm::vec3(0.0f));
  m.albedo = glm::min(m.albedo, glm::vec3(1.0f));
  m.ks = glm::min(m.ks, room);
  report.warnings.push_back(where + ": material '" + m.name + "': albedo + ks = " + std::to_string(worst) +
                            " > 1; ks reduced to conserve energy");
}

// ---------------------------------------------------------------- JSON helpers
struct JsonCtx {
  std::string file;
  [[noreturn]] void error(const std::string& where, const std::string& what) const {
    fail(file, ": ", where, ": ", what);
  }
  void checkKeys(const json& j, const std::string& where, std::set<std::string> allowed) const {
    if (!j.is_object()) error(where, "expected an object, got " + jsonExcerpt(j));
    for (auto& [k, v] : j.items())
      if (!allowed.count(k)) {
        std::string list;
        for (auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        error(where, "unknown key '" + k + "' (allowed: " + list + ")");
      }
  }
  // Checked in float, the type it is stored in: 1e39 is a finite double but
  // an infinite float.
  float number(const json& j, const std::string& where) const {
    if (!j.is_number()) error(where, "expected a number, got " + jsonExcerpt(j));
    double v = j.get<double>();
    if (!std::isfinite(v) || std::abs(v) > double(std::numeric_limits<float>::max()))
      error(where, "expected a finite number within float range (|x| <= 3.4e38), got " + jsonExcerpt(j));
    return float(v);
  }
  glm::vec3 vec3(const json& j, const std::string& where) const {
    if (!j.is_array() || j.size() != 3) error(where, "expected an array of 3 numbers, got " + jsonExcerpt(j));
    return {number(j[0], where + "[0]"), number(j[1], where + "[1]"), number(j[2], where + "[2]")};
  }
  // A colour: [r,g,b] or one number for grey; never negative.
  glm::vec3 color(const json& j, const std::string& where) const {
    glm::vec3 c = j.is_number() ? glm::vec3(number(j, where)) : vec3(j, where);
    if (c.x < 0 || c.y < 0 || c.z < 0) error(where, "must not be negative, got " + jsonExcerpt(j));
    return c;
  }
  glm::vec3 direction(const json& j, const std::string& where) const {
    glm::vec3 d = vec3(j, where);
    if (glm::length(d) < 1e-12f) error(where, "direction must not be zero, got " + jsonExcerpt(j));
    return glm::normalize(d);
  }
  std::string string(const json& j, const std::string& where) const {
    if (!j.is_string()) error(where, "expected a string, got " + jsonExcerpt(j));
    return j.get<std::string>();
  }
  bool boolean(const json& j, const std::string& where) const {
    if (!j.is_boolean()) error(where, "expected true or false, got " + jsonExcerpt(j));
    return j.get<bool>();
  }
};

// translate/rotate/scale (applied as T·R·S) into a keyframe-like triple.
Keyframe readTrs(const JsonCtx& c, const json& j, const std::string& where) {
  Keyframe k;
  if (j.contains("translate")) k.translation = c.vec3(j["translate"], where + ".translate");
  if (j.contains("rotate")) {
    const json& r = j["rotate"];
    if (!r.is_array() || r.size() != 4)
      c.error(where + ".rotate", "expected [angle_deg, axis_x, axis_y, axis_z], got " + jsonExcerpt(r));
    float deg = c.number(r[0], where + ".rotate[0]");
    glm::vec3 axis = c.direction(json::array({r[1], r[2], r[3]}), where + ".rotate axis");
    k.rotation = glm::angleAxis(glm::radians(deg), axis);
  }
  if (j.contains("scale")) {
    const json& s = j["scale"];
    k.scale = s.is_number() ? glm::vec3(c.number(s, where + ".scale")) : c.vec3(s, where + ".scale");
    if (k.scale.x == 0 || k.scale.y == 0 || k.scale.z == 0)
      c.error(where + ".scale", "must not be zero, got " + jsonExcerpt(s));
  }
  return k;
}

glm::mat4 trsMatrix(const Keyframe& k) {
  glm::mat4 m = glm::translate(glm::mat4(1.0f), k.translation) * glm::mat4_cast(k.rotation);
  return glm::scale(m, k.scale);
}

glm::mat4 readTransform(const JsonCtx& c, const json& j, const std::string& where) {
  c.checkKeys(j, where, {"translate", "rotate", "scale", "matrix"});
  if (j.contains("matrix")) {
    if (j.size() != 1) c.error(where, "'matrix' cannot be combined with translate/rotate/scale");
    const json& m = j["matrix"];
    if (!m.is_array() || m.size() != 16)
      c.error(where + ".matrix", "expected 16 numbers (row-major), got " + jsonExcerpt(m));
    glm::mat4 r;
    for (int row = 0; row < 4; ++row)
      for (int col = 0; col < 4; ++col)
        r[col][row] = c.number(m[row * 4 + col], where + ".matrix[" + std::to_string(row * 4 + col) + "]");
    if (std::abs(glm::determinant(glm::mat3(r))) < 1e-20f) c.error(where + ".matrix", "is singular");
    return r;
  }
  return trsMatrix(readTrs(c, j, where));
}

void readMaterialOverride(const JsonCtx& c, const json& j, const std::string& where, Material& m,
                          Scene& scene, const fs::path& dir) {
  c.checkKeys(j, where, {"albedo", "texture", "ks", "exponent", "emission"});
  if (j.contains("albedo")) m.albedo = c.color(j["albedo"], where + ".albedo");
  if (j.contains("ks")) m.ks = c.color(j["ks"], where + ".ks");
  if (j.contains("emission")) m.emission = c.color(j["emission"], where + ".emission");
  if (j.contains("exponent")) {
    m.exponent = c.number(j["exponent"], where + ".exponent");
    if (m.exponent < 0 || m.exponent > 1e5f)
      c.error(where + ".exponent", "must be in [0, 100000], got " + jsonExcerpt(j["exponent"]));
  }
  if (j.contains("texture")) {
    // The scene file names this texture itself: one it cannot read is refused, never replaced by the
    // constant albedo (a model file's missing texture only warns: its author is not the user).
    std::string p = (dir / c.string(j["texture"], where + ".texture")).string();
    try {
      scene.textures.push_back(loadTexture(p));
    } catch (const Error& e) {
      c.error(where + ".texture", e.what());
    }
    m.albedoTexture = int(scene.textures.size()) - 1;
  }
  conserveEnergy(m, c.file + ": " + where, scene.report);
}

// "keyframes" of a light: a path, each key's position (point, spot) and direction (spot,
// directional) over the light's own, times increasing (Scene::placeLightsAt).
void readLightPath(const JsonCtx& c, const json& kj, const std::string& where, Light& l) {
  if (!kj.is_array() || kj.empty()) c.error(where, "expected a non-empty array");
  const bool moves = l.type != LightType::Directional, turns = l.type != LightType::Point;
  for (size_t k = 0; k < kj.size(); ++k) {
    const std::string kw = where + "[" + std::to_string(k) + "]";
    std::set<std::string> keys = {"time"};
    if (moves) keys.insert("position");
    if (turns) keys.insert("direction");
    c.checkKeys(kj[k], kw, keys);
    if (!kj[k].contains("time")) c.error(kw, "missing \"time\"");
    LightKey key;
    key.time = c.number(kj[k]["time"], kw + ".time");
    if (!l.keyframes.empty() && key.time <= l.keyframes.back().time)
      c.error(kw + ".time", "keyframe times must increase");
    key.position = kj[k].contains("position") ? c.vec3(kj[k]["position"], kw + ".position") : l.position;
    key.direction =
        kj[k].contains("direction") ? c.direction(kj[k]["direction"], kw + ".direction") : l.direction;
    l.keyframes.push_back(key);
  }
}

Light readLight(const JsonCtx& c, const json& j, const std::string& where) {
  if (!j.is_object() || !j.contains("type"))
    c.error(where, "a light needs a \"type\" (spot, point, directional)");
  std::string type = c.string(j["type"], where + ".type");
  Light l;
  auto intensity = [&](const char* key) {
    if (!j.contains(key)) c.error(where, std::string("missing \"") + key + "\"");
    return c.color(j[key], where + "." + key);
  };
  if (type == "point") {
    c.checkKeys(j, where, {"type", "position", "intensity", "keyframes"});
    l.type = LightType::Point;
    if (!j.contains("position")) c.error(where, "missing \"position\"");
    l.position = c.vec3(j["position"], where + ".position");
    l.intensity = intensity("intensity");
  } else if (type == "spot") {
    c.checkKeys(j, where, {"type", "position", "direction", "intensity", "cone_deg", "falloff", "keyframes"});
    l.type = LightType::Spot;
    if (!j.contains("position")) c.error(where, "missing \"position\"");
    if (!j.contains("direction")) c.error(where, "missing \"direction\"");
    l.position = c.vec3(j["position"], where + ".position");
    l.direction = c.direction(j["direction"], where + ".direction");
    l.intensity = intensity("intensity");
    if (j.contains("cone_deg")) {
      l.coneHalfAngleDeg = c.number(j["cone_deg"], where + ".cone_deg");
      if (l.coneHalfAngleDeg <= 0 || l.coneHalfAngleDeg > 90)
        c.error(where + ".cone_deg", "half-angle must be in (0, 90], got " + jsonExcerpt(j["cone_deg"]));
    }
    if (j.contains("falloff")) {
      l.falloff = c.number(j["falloff"], where + ".falloff");
      if (l.falloff < 0 || l.falloff > 1000)
        c.error(where + ".falloff", "must be in [0, 1000], got " + jsonExcerpt(j["falloff"]));
    }
  } else if (type == "directional") {
    c.checkKeys(j, where, {"type", "direction", "irradiance", "keyframes"});
    l.type = LightType::Directional;
    if (!j.contains("direction")) c.error(where, "missing \"direction\"");
    l.direction = c.direction(j["direction"], where + ".direction");
    l.intensity = intensity("irradiance");
  } else {
    c.error(where + ".type", "unknown light type '" + type + "' (spot, point, directional)");
  }
  if (j.contains("keyframes")) readLightPath(c, j["keyframes"], where + ".keyframes", l);
  return l;
}

Camera defaultCamera(const Bounds& b) {
  Camera cam;
  glm::vec3 c = 0.5f * (b.lo + b.hi);
  float r = std::max(0.5f * b.diagonal(), 1e-6f);
  cam.fovYDeg = 45.0f;
  cam.target = c;
  cam.position = c + glm::vec3(0.0f, 0.25f * r, r / std::tan(glm::radians(22.5f)) * 1.05f);
  return cam;
}

void checkCameraPose(const Camera& cam, const std::string& where) {
  glm::vec3 dir = cam.target - cam.position;
  if (glm::length(dir) < 1e-12f) fail(where, " position equals its target");
  if (glm::length(glm::cross(dir, cam.up)) < 1e-12f * glm::length(dir))
    fail(where, " 'up' is parallel to the viewing direction");
}

void finishScene(Scene& scene, const std::string& origin, bool haveLights, bool haveCamera) {
  if (scene.triangleCount() == 0) fail(origin, ": the scene has no triangles");
  checkSceneRanges(scene, origin);
  Bounds b = scene.bounds();
  if (!haveCamera) scene.camera = defaultCamera(b);
  if (!haveLights && scene.lights.empty()) {
    bool emissive = false;
    for (auto& m : scene.materials) emissive |= m.emission != glm::vec3(0.0f);
    if (!emissive && scene.environment.isBlack()) {
      Light l;
      l.type = LightType::Point;
      l.position = scene.camera.position + glm::vec3(0, 0.3f * b.diagonal(), 0);
      l.intensity = glm::vec3(0.25f * b.diagonal() * b.diagonal());
      scene.lights.push_back(l);
      scene.report.warnings.push_back(origin + ": no lights, added a point light above the camera");
    }
  }
  checkCameraPose(scene.camera, origin + ": camera");
  for (size_t k = 0; k < scene.cameraPath.size(); ++k)
    checkCameraPose(scene.cameraPath[k].camera, origin + ": camera.keyframes[" + std::to_string(k) + "]");
}

// A mesh entry's keyframes (it must be dynamic), times increasing.
std::vector<Keyframe> readKeyframes(JsonCtx& c, const json& mj, const std::string& where, bool dynamic) {
  std::vector<Keyframe> keys;
  if (!mj.contains("keyframes")) return keys;
  const json& kj = mj["keyframes"];
  if (!kj.is_array()) c.error(where + ".keyframes", "expected an array");
  if (!dynamic) c.error(where + ".keyframes", "keyframes need \"dynamic\": true");
  for (size_t k = 0; k < kj.size(); ++k) {
    std::string kw = where + ".keyframes[" + std::to_string(k) + "]";
    c.checkKeys(kj[k], kw, {"time", "translate", "rotate", "scale"});
    if (!kj[k].contains("time")) c.error(kw, "missing \"time\"");
    Keyframe key = readTrs(c, kj[k], kw);
    key.time = c.number(kj[k]["time"], kw + ".time");
    if (!keys.empty() && key.time <= keys.back().time) c.error(kw + ".time", "keyframe times must increase");
    keys.push_back(key);
  }
  return keys;
}

// What the builtin scenes of a scene file bring beside their meshes.
struct BuiltinExtras {
  std::vector<Light> lights;
  Camera camera;
  bool haveCamera = false;
};

// The material a mesh entry names: a loaded one, or a new one defined under "materials".
int readMeshMaterial(JsonCtx& c, const json& mj, const std::string& where, Scene& scene,
                     const json& materialsJson) {
  if (!mj.contains("material")) return -1;
  std::string name = c.string(mj["material"], where + ".material");
  for (size_t k = scene.materials.size(); k-- > 0;)  // the last of that name (files may share names)
    if (scene.materials[k].name == name) return int(k);
  if (!materialsJson.contains(name))
    c.error(where + ".material", "no material named '" + name + "' (define it under \"materials\")");
  Material m;
  m.name = name;
  scene.materials.push_back(m);
  return int(scene.materials.size()) - 1;
}

// One entry of "meshes": its file (or builtin scene), transform, material, motion.
void readMeshEntry(JsonCtx& c, const json& mj, const std::string& where, const fs::path& dir, Scene& scene,
                   const json& materialsJson, BuiltinExtras& builtin) {
  c.checkKeys(mj, where, {"path", "transform", "material", "dynamic", "keyframes"});
  if (!mj.contains("path")) c.error(where, "missing \"path\"");
  std::string p = c.string(mj["path"], where + ".path");
  size_t first = scene.meshes.size();
  if (p.rfind("builtin:", 0) == 0) {
    appendBuiltin(p.substr(8), scene, builtin.lights, builtin.camera);
    builtin.haveCamera = true;
  } else {
    appendModelFile((dir / p).string(), scene);
  }
  glm::mat4 T(1.0f);
  if (mj.contains("transform")) T = readTransform(c, mj["transform"], where + ".transform");
  const int forcedMaterial = readMeshMaterial(c, mj, where, scene, materialsJson);
  bool dynamic = mj.contains("dynamic") && c.boolean(mj["dynamic"], where + ".dynamic");
  const std::vector<Keyframe> keys = readKeyframes(c, mj, where, dynamic);
  for (size_t m = first; m < scene.meshes.size(); ++m) {
    scene.meshes[m].transform = T * scene.meshes[m].transform;
    scene.meshes[m].dynamic = dynamic;
    scene.meshes[m].keyframes = keys;
    if (forcedMaterial >= 0) scene.meshes[m].material = forcedMaterial;
  }
}

// An entry of "materials" overrides every loaded material of that name (files
// may share names), or defines a new material.
void applyMaterialEntries(JsonCtx& c, const json& materialsJson, Scene& scene, const fs::path& dir) {
  for (auto& [name, mj] : materialsJson.items()) {
    bool found = false;
    for (size_t k = 0; k < scene.materials.size(); ++k)
      if (scene.materials[k].name == name) {
        found = true;
        Material m = scene.materials[k];
        readMaterialOverride(c, mj, "materials." + name, m, scene, dir);
        scene.materials[k] = m;
      }
    if (!found) {
      Material m;
      m.name = name;
      readMaterialOverride(c, mj, "materials." + name, m, scene, dir);
      scene.materials.push_back(m);
    }
  }
}

void readEnvironment(JsonCtx& c, const json& ej, Scene& scene, const fs::path& dir) {
  c.checkKeys(ej, "environment", {"color", "map", "scale"});
  if (ej.contains("color")) scene.environment.color = c.color(ej["color"], "environment.color");
  if (ej.contains("scale")) {
    scene.environment.scale = c.number(ej["scale"], "environment.scale");
    if (scene.environment.scale < 0) c.error("environment.scale", "must not be negative");
  }
  if (ej.contains("map")) {
    // Refused, not replaced by the constant colour: the image would not be what the file asks for.
    std::string p = (dir / c.string(ej["map"], "environment.map")).string();
    try {
      scene.textures.push_back(loadTexture(p, "environment map"));
    } catch (const Error& e) {
      c.error("environment.map", e.what());
    }
    scene.environment.mapTexture = int(scene.textures.size()) - 1;
  }
}

// A camera's position, target, up and field of view over `cam` (each optional when `base`).
void readCameraPose(JsonCtx& c, const json& cj, const std::string& where, bool base, Camera& cam) {
  if (base && (!cj.contains("position") || !cj.contains("target")))
    c.error(where, "needs \"position\" and \"target\"");
  if (cj.contains("position")) cam.position = c.vec3(cj["position"], where + ".position");
  if (cj.contains("target")) cam.target = c.vec3(cj["target"], where + ".target");
  if (cj.contains("up")) cam.up = c.direction(cj["up"], where + ".up");
  if (cj.contains("fov_deg")) {
    cam.fovYDeg = c.number(cj["fov_deg"], where + ".fov_deg");
    if (cam.fovYDeg <= 0 || cam.fovYDeg >= 180)
      c.error(where + ".fov_deg", "must be in (0, 180), got " + jsonExcerpt(cj["fov_deg"]));
  }
}

// "camera": the pose, the cut-away distance "near", and "keyframes" (a path: each key's pose over
// the camera's, times increasing).
Camera readCamera(JsonCtx& c, const json& cj, std::vector<CameraKey>& path) {
  c.checkKeys(cj, "camera", {"position", "target", "up", "fov_deg", "near", "keyframes"});
  Camera cam;
  readCameraPose(c, cj, "camera", true, cam);
  if (cj.contains("near")) {
    cam.clipNear = c.number(cj["near"], "camera.near");
    if (!(cam.clipNear > 0)) c.error("camera.near", "must be > 0, got " + jsonExcerpt(cj["near"]));
  }
  path.clear();
  if (cj.contains("keyframes")) {
    const json& kj = cj["keyframes"];
    if (!kj.is_array() || kj.empty()) c.error("camera.keyframes", "expected a non-empty array");
    for (size_t k = 0; k < kj.size(); ++k) {
      const std::string kw = "camera.keyframes[" + std::to_string(k) + "]";
      c.checkKeys(kj[k], kw, {"time", "position", "target", "up", "fov_deg"});
      if (!kj[k].contains("time")) c.error(kw, "missing \"time\"");
      CameraKey key;
      key.time = c.number(kj[k]["time"], kw + ".time");
      if (!path.empty() && key.time <= path.back().time)
        c.error(kw + ".time", "keyframe times must increase");
      key.camera = cam;
      readCameraPose(c, kj[k], kw, false, key.camera);
      path.push_back(key);
    }
  }
  return cam;
}

void readPresets(JsonCtx& c, const json& pj, Scene& scene) {
  if (!pj.is_object()) c.error("presets", "expected an object of name → {key: value}");
  for (auto& [name, kv] : pj.items()) {
    if (!kv.is_object()) c.error("presets." + name, "expected an object of key → value");
    for (auto& [k, v] : kv.items()) {
      if (v.is_string())
        scene.presets[name][k] = v.get<std::string>();
      else if (v.is_number() || v.is_boolean())
        scene.presets[name][k] = jsonText(v);
      else
        c.error("presets." + name + "." + k, "expected a string, number or boolean, got " + jsonExcerpt(v));
    }
  }
}

Scene loadSceneJson(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("cannot open scene file '", path, "'");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) fail("cannot read scene file '", path, "'");
  const json root = parseJsonText(text, path);
  JsonCtx c{path};
  c.checkKeys(root, "top level",
              {"meshes", "materials", "lights", "environment", "camera", "presets", "two_sided_emission"});
  fs::path dir = fs::path(path).parent_path();
  Scene scene;
  scene.name = fs::path(path).stem().string();
  if (!root.contains("meshes") || !root["meshes"].is_array() || root["meshes"].empty())
    c.error("meshes", "expected a non-empty array of meshes");
  static const json noMaterials = json::object();  // a reference either way: never a copy of the scene's
  const json& materialsJson = root.contains("materials") ? root["materials"] : noMaterials;
  if (!materialsJson.is_object()) c.error("materials", "expected an object of name → material");
  BuiltinExtras builtin;
  for (size_t i = 0; i < root["meshes"].size(); ++i)
    readMeshEntry(c, root["meshes"][i], "meshes[" + std::to_string(i) + "]", dir, scene, materialsJson,
                  builtin);
  applyMaterialEntries(c, materialsJson, scene, dir);
  bool haveLights = false;
  if (root.contains("lights")) {
    const json& lj = root["lights"];
    if (!lj.is_array()) c.error("lights", "expected an array");
    for (size_t i = 0; i < lj.size(); ++i)
      scene.lights.push_back(readLight(c, lj[i], "lights[" + std::to_string(i) + "]"));
    haveLights = true;
  } else {
    scene.lights = builtin.lights;
    haveLights = !builtin.lights.empty();
  }
  if (root.contains("two_sided_emission"))
    scene.twoSidedEmission = c.boolean(root["two_sided_emission"], "two_sided_emission");
  if (root.contains("environment")) readEnvironment(c, root["environment"], scene, dir);
  bool haveCamera = builtin.haveCamera;
  scene.camera = builtin.camera;
  if (root.contains("camera")) {
    scene.camera = readCamera(c, root["camera"], scene.cameraPath);
    haveCamera = true;
  }
  if (root.contains("presets")) readPresets(c, root["presets"], scene);
  finishScene(scene, path, haveLights, haveCamera);
  return scene;
}

// ---------------------------------------------------------------- assimp
struct AssimpReader {
  const aiScene* ai;
  std::string path;
  fs::path dir;
  Scene& scene;
  int materialBase;
  std::map<std::string, int> textureCache;
  size_t appended = 0;

  int texture(const std::string& rel, const std::string& materialName) {
    if (!rel.empty() && rel[0] == '*') {
      scene.report.warnings.push_back(path + ": material '" + materialName +
                                      "': embedded textures are not supported, using its constant albedo");
      return -1;
    }
    std::string p = (dir / rel).string();
    auto it = textureCache.find(p);
    if (it != textureCache.end()) return it->second;
    int idx = -1;
    try {
      scene.textures.push_back(loadTexture(p));
      idx = int(scene.textures.size()) - 1;
    } catch (const Error& e) {
      scene.report.warnings.push_back(std::string(e.what()) + " (material '" + materialName +
                                      "' uses its constant albedo)");
    }
    textureCache[p] = idx;
    return idx;
  }

  void materials() {
    for (unsigned i = 0; i < ai->mNumMaterials; ++i) {
      const aiMaterial* am = ai->mMaterials[i];
      Material m;
      aiString name;
      if (am->Get(AI_MATKEY_NAME, name) == AI_SUCCESS) m.name = name.C_Str();
      // Formats without materials (PLY, bare OBJ) get assimp's default material,
      // which is white diffuse *and* white specular; use our default instead.
      if (m.name.empty() || m.name == AI_DEFAULT_MATERIAL_NAME) {
        m.name = fs::path(path).stem().string() + "_default";
        scene.materials.push_back(m);
        continue;
      }
      aiColor3D c;
      if (am->Get(AI_MATKEY_BASE_COLOR, c) == AI_SUCCESS || am->Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS)
        m.albedo = {c.r, c.g, c.b};
      if (am->Get(AI_MATKEY_COLOR_SPECULAR, c) == AI_SUCCESS) m.ks = {c.r, c.g, c.b};
      if (am->Get(AI_MATKEY_COLOR_EMISSIVE, c) == AI_SUCCESS) m.emission = {c.r, c.g, c.b};
      float shininess = 0;
      if (am->Get(AI_MATKEY_SHININESS, shininess) == AI_SUCCESS && std::isfinite(shininess))
        m.exponent = std::max(shininess, 0.0f);
      if (!finite3(m.albedo) || !finite3(m.ks) || !finite3(m.emission))
        fail(path, ": material '", m.name, "' has non-finite colours");
      m.albedo = glm::clamp(m.albedo, 0.0f, 1.0f);
      m.ks = glm::clamp(m.ks, 0.0f, 1.0f);
      m.emission = glm::max(m.emission, 0.0f);
      aiString tex;
      if (am->GetTexture(aiTextureType_BASE_COLOR, 0, &tex) == AI_SUCCESS ||
          am->GetTexture(aiTextureType_DIFFUSE, 0, &tex) == AI_SUCCESS)
        m.albedoTexture = texture(tex.C_Str(), m.name);
      // Textures modulate; a black Kd next to a map_Kd would hide the map.
      if (m.albedoTexture >= 0 && m.albedo == glm::vec3(0.0f)) m.albedo = glm::vec3(1.0f);
      conserveEnergy(m, path, scene.report);
      scene.materials.push_back(m);
    }
  }

  // assimp's default material stands for the faces that name none; where every face names one
  // (Sibenik's OBJ, a glTF with materials) nothing uses it, and it is not kept (`vgi info` listed a
  // material more than the model has, issue 64).
  void dropUnusedDefault() {
    const std::string name = fs::path(path).stem().string() + "_default";
    for (int i = int(scene.materials.size()) - 1; i >= materialBase; --i) {
      if (scene.materials[size_t(i)].name != name) continue;
      if (std::any_of(scene.meshes.begin(), scene.meshes.end(),
                      [&](const Mesh& m) { return m.material == i; }))
        continue;
      scene.materials.erase(scene.materials.begin() + i);
      for (Mesh& m : scene.meshes)
        if (m.material > i) --m.material;
    }
  }

  void node(const aiNode* n, const glm::mat4& parent) {
    glm::mat4 local = glm::transpose(glm::make_mat4(&n->mTransformation.a1));
    glm::mat4 M = parent * local;
    for (unsigned k = 0; k < n->mNumMeshes; ++k) mesh(ai->mMeshes[n->mMeshes[k]], M);
    for (unsigned k = 0; k < n->mNumChildren; ++k) node(n->mChildren[k], M);
  }

  // A mesh without normals gets smooth ones (core/smooth_normals.h); a vertex on a crease is split
  // into one vertex per side, the others stay shared (the atlas's charts follow the connectivity).
  void addSmoothNormals(Mesh& m) {
    SmoothNormals sn = smoothCornerNormals(m.positions, m.triangles, kMaxSmoothingAngleDegrees,
                                           kMaxDistinctNormalsPerPosition);
    if (sn.flatPositions > 0)
      scene.report.warnings.push_back(path + ": mesh '" + m.name + "': " + std::to_string(sn.flatPositions) +
                                      " vertex position(s) shared by more than " +
                                      std::to_string(kMaxDistinctNormalsPerPosition) +
                                      " differently oriented triangles keep flat normals");
    WeldedNormals w = weldCornerNormals(m.triangles, sn.normals);
    Mesh u;
    for (uint32_t v : w.source) {
      u.positions.push_back(m.positions[v]);
      if (!m.uvs.empty()) u.uvs.push_back(m.uvs[v]);
    }
    m.positions.swap(u.positions);
    m.uvs.swap(u.uvs);
    m.triangles.swap(w.triangles);
    m.normals = std::move(w.normals);
  }

  void mesh(const aiMesh* am, const glm::mat4& M) {
    if (!(am->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) return;  // points/lines sorted out
    Mesh m;
    m.name = am->mName.length ? am->mName.C_Str() : fs::path(path).stem().string();
    m.source = path;
    m.material = materialBase + int(am->mMaterialIndex);
    m.transform = M;
    m.positions.resize(am->mNumVertices);
    for (unsigned v = 0; v < am->mNumVertices; ++v)
      m.positions[v] = {am->mVertices[v].x, am->mVertices[v].y, am->mVertices[v].z};
    if (am->mNormals) {
      m.normals.resize(am->mNumVertices);
      for (unsigned v = 0; v < am->mNumVertices; ++v)
        m.normals[v] = {am->mNormals[v].x, am->mNormals[v].y, am->mNormals[v].z};
    }
    if (am->mTextureCoords[0]) {
      m.uvs.resize(am->mNumVertices);
      for (unsigned v = 0; v < am->mNumVertices; ++v)
        m.uvs[v] = {am->mTextureCoords[0][v].x, am->mTextureCoords[0][v].y};
    }
    for (unsigned f = 0; f < am->mNumFaces; ++f) {
      const aiFace& face = am->mFaces[f];
      if (face.mNumIndices != 3) continue;
      m.triangles.push_back({face.mIndices[0], face.mIndices[1], face.mIndices[2]});
    }
    if (!am->mNormals) addSmoothNormals(m);
    validateMesh(m, scene.report);
    if (!m.triangles.empty()) {
      scene.meshes.push_back(std::move(m));
      ++appended;
    }
  }
};

}  // namespace

void validateMesh(Mesh& m, LoadReport& report) {
  for (size_t v = 0; v < m.positions.size(); ++v)
    if (!finite3(m.positions[v]))
      fail(m.source, ": mesh '", m.name, "': vertex ", v, " has a non-finite coordinate (", m.positions[v].x,
           ", ", m.positions[v].y, ", ", m.positions[v].z, ")");
  if (!m.normals.empty() && m.normals.size() != m.positions.size())
    fail(m.source, ": mesh '", m.name, "': ", m.normals.size(), " normals for ", m.positions.size(),
         " vertices");
  if (!m.uvs.empty() && m.uvs.size() != m.positions.size())
    fail(m.source, ": mesh '", m.name, "': ", m.uvs.size(), " uvs for ", m.positions.size(), " vertices");
  for (auto& n : m.normals)
    if (!finite3(n) || glm::length(n) < 1e-20f)
      n = glm::vec3(0.0f);  // flatten() falls back to the face normal
  for (auto& uv : m.uvs)
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = glm::vec2(0.0f);
  std::vector<glm::uvec3> kept;
  kept.reserve(m.triangles.size());
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    const glm::uvec3& tri = m.triangles[t];
    for (int k = 0; k < 3; ++k)
      if (tri[k] >= m.positions.size())
        fail(m.source, ": mesh '", m.name, "': triangle ", t, " uses vertex index ", tri[k],
             " but the mesh has ", m.positions.size(), " vertices");
    glm::vec3 a = m.positions[tri[0]], b = m.positions[tri[1]], c = m.positions[tri[2]];
    glm::vec3 cr = glm::cross(b - a, c - a);
    float scale = std::max({glm::length(b - a), glm::length(c - a), glm::length(c - b)});
    // Zero area relative to the triangle's own size: cross product below float resolution.
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] ||
        !(glm::length(cr) > 1e-7f * scale * scale)) {
      ++report.degenerateTrianglesDropped;
      continue;
    }
    kept.push_back(tri);
  }
  m.triangles.swap(kept);
}

void requireRegularFile(const std::string& path, const std::string& what) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec && ec != std::errc::no_such_file_or_directory) fail(what, " '", path, "': ", ec.message());
  if (!fs::exists(st)) fail(what, " '", path, "' does not exist");
  if (fs::is_directory(st)) fail(what, " '", path, "' is a directory");
  if (!fs::is_regular_file(st))
    fail(what, " '", path, "' is not a regular file (a device, FIFO or socket cannot be read as one)");
}

Texture loadTexture(const std::string& path, const std::string& what) {
  requireRegularFile(path, what);
  const image_io::Pixels in = image_io::read(path, what);
  const std::vector<float>& px = in.values;
  const int nc = in.channels;
  const bool srgb = in.srgb;
  Texture t;
  t.path = path;
  t.srgb = srgb;
  t.width = in.width;
  t.height = in.height;
  t.texels.resize(size_t(t.width) * t.height);
  for (size_t i = 0; i < t.texels.size(); ++i) {
    glm::vec3 c;
    for (int k = 0; k < 3; ++k) {
      float v = px[i * nc + std::min(k, nc >= 3 ? k : 0)];
      if (!std::isfinite(v)) {
        v = 0;
        if (k == 0 || nc >= 3) ++t.nonFiniteTexels;
      }
      c[k] = srgb ? srgbToLinear(v) : v;
    }
    t.texels[i] = c;
  }
  return t;
}

size_t appendModelFile(const std::string& path, Scene& scene) {
  requireRegularFile(path, "model file");
  std::string ext = lower(fs::path(path).extension().string());
  if (ext != ".obj" && ext != ".gltf" && ext != ".glb" && ext != ".ply")
    fail("model file '", path, "': unsupported format '", ext, "' (obj, gltf, glb, ply)");
  Assimp::Importer importer;
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // Read with triangulation only and check the raw vertices first: later steps
  // (vertex joining, normal generation) silently drop triangles with NaN corners.
  const aiScene* ai = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_ValidateDataStructure);
  if (!ai) fail("cannot load model '", path, "': ", importer.GetErrorString());
  for (unsigned m = 0; m < ai->mNumMeshes; ++m) {
    const aiMesh* am = ai->mMeshes[m];
    for (unsigned v = 0; v < am->mNumVertices; ++v) {
      glm::vec3 p(am->mVertices[v].x, am->mVertices[v].y, am->mVertices[v].z);
      if (!finite3(p))
        fail(path, ": mesh '", am->mName.C_Str(), "': vertex ", v, " has a non-finite coordinate (", p.x,
             ", ", p.y, ", ", p.z, ")");
    }
  }
  // Normals are not generated here (aiProcess_GenSmoothNormals is quadratic in the corners at one
  // position: AssimpReader::addSmoothNormals does it in linear time).
  ai = importer.ApplyPostProcessing(aiProcess_JoinIdenticalVertices | aiProcess_SortByPType |
                                    aiProcess_ValidateDataStructure);
  if (!ai) fail("cannot load model '", path, "': ", importer.GetErrorString());
  if (ai->mFlags & AI_SCENE_FLAGS_INCOMPLETE) fail("model '", path, "' is incomplete (no meshes?)");
  AssimpReader r{ai, path, fs::path(path).parent_path(), scene, int(scene.materials.size()), {}, 0};
  r.materials();
  if (ai->mRootNode) r.node(ai->mRootNode, glm::mat4(1.0f));
  r.dropUnusedDefault();
  if (r.appended == 0) fail("model '", path, "' has no (non-degenerate) triangles");
  return r.appended;
}

Scene loadScene(const std::string& spec) {
  if (spec.rfind("builtin:", 0) == 0) {
    Scene s;
    s.name = spec;
    std::vector<Light> lights;
    appendBuiltin(spec.substr(8), s, lights, s.camera);
    s.lights = lights;
    finishScene(s, spec, true, true);
    return s;
  }
  requireRegularFile(spec, "scene");
  if (lower(fs::path(spec).extension().string()) == ".json") return loadSceneJson(spec);
  Scene s;
  s.name = fs::path(spec).stem().string();
  appendModelFile(spec, s);
  finishScene(s, spec, false, false);
  return s;
}

}  // namespace vgi
