#include "core/scene.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "shaders/shared/cpp_prelude.h"
#include "shaders/shared/environment.glsl"

namespace vgi {

glm::vec3 Texture::lookup(glm::vec2 uv, bool wrapV) const {
  if (texels.empty()) return glm::vec3(1.0f);
  float v = wrapV ? uv.y - std::floor(uv.y) : glm::clamp(uv.y, 0.0f, 1.0f);
  float x = (uv.x - std::floor(uv.x)) * width - 0.5f;
  float y = (1.0f - v) * height - 0.5f;  // uv origin bottom-left
  int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  float fx = x - x0, fy = y - y0;
  auto at = [&](int i, int j) {
    i = ((i % width) + width) % width;
    j = wrapV ? ((j % height) + height) % height : glm::clamp(j, 0, height - 1);
    return texels[size_t(j) * width + i];
  };
  return glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), fx), glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), fx),
                  fy);
}

float keyFraction(float time, float a, float b) {
  if (!(b > a)) return 0.0f;
  const double t = (double(time) - double(a)) / (double(b) - double(a));
  return float(std::clamp(t, 0.0, 1.0));
}

glm::mat4 Mesh::objectToWorld(float time) const {
  if (!dynamic || keyframes.empty()) return transform;
  const Keyframe* a = &keyframes.front();
  const Keyframe* b = a;
  if (time >= keyframes.back().time) {
    a = b = &keyframes.back();
  } else {
    for (size_t i = 0; i + 1 < keyframes.size(); ++i)
      if (time >= keyframes[i].time && time < keyframes[i + 1].time) {
        a = &keyframes[i];
        b = &keyframes[i + 1];
      }
  }
  const float t = keyFraction(time, a->time, b->time);
  glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::mix(a->translation, b->translation, t));
  m = m * glm::mat4_cast(glm::slerp(a->rotation, b->rotation, t));
  m = glm::scale(m, glm::mix(a->scale, b->scale, t));
  return m * transform;
}

bool Scene::hasLightPaths() const {
  return std::any_of(lights.begin(), lights.end(), [](const Light& l) { return !l.keyframes.empty(); });
}

void Scene::placeLightsAt(float time) {
  for (Light& l : lights) {
    const std::vector<LightKey>& keys = l.keyframes;
    if (keys.empty()) continue;
    size_t i = 0;
    while (i + 2 < keys.size() && time >= keys[i + 1].time) ++i;
    const LightKey &a = keys[i], &b = keys[std::min(i + 1, keys.size() - 1)];
    const float t = keyFraction(time, a.time, b.time);
    l.position = glm::mix(a.position, b.position, t);
    const glm::vec3 d = glm::mix(a.direction, b.direction, t);
    l.direction = glm::length(d) > 1e-3f ? glm::normalize(d) : (t < 0.5f ? a.direction : b.direction);
  }
}

Camera Scene::cameraAt(float time) const {
  if (cameraPath.empty()) return camera;
  if (time <= cameraPath.front().time) return cameraPath.front().camera;
  if (time >= cameraPath.back().time) return cameraPath.back().camera;
  size_t i = 0;
  while (time >= cameraPath[i + 1].time) ++i;
  const CameraKey &a = cameraPath[i], &b = cameraPath[i + 1];
  const float t = keyFraction(time, a.time, b.time);
  Camera c = a.camera;
  c.position = glm::mix(a.camera.position, b.camera.position, t);
  c.target = glm::mix(a.camera.target, b.camera.target, t);
  c.up = glm::mix(a.camera.up, b.camera.up, t);
  c.fovYDeg = glm::mix(a.camera.fovYDeg, b.camera.fovYDeg, t);
  // The loader checks every key's pose; between two keys the position can pass through the target,
  // the up can shrink to nothing (keys (0,1,0) → (0,−1,0) meet at the zero vector) or turn parallel
  // to the view: there the nearer key's camera stands in. Each test is relative to the keys' own
  // lengths, so a zero or vanishing vector fails it (a bound scaled by the interpolated length did not).
  const glm::vec3 dir = c.target - c.position;
  const float dirLen = glm::length(dir), upLen = glm::length(c.up);
  const float keyDir = std::max(glm::length(a.camera.target - a.camera.position),
                                glm::length(b.camera.target - b.camera.position)),
              keyUp = std::max(glm::length(a.camera.up), glm::length(b.camera.up));
  if (!(dirLen > 1e-6f * keyDir) || !(upLen > 1e-3f * keyUp) ||
      !(glm::length(glm::cross(dir / dirLen, c.up / upLen)) > 1e-3f))
    return t < 0.5f ? a.camera : b.camera;
  return c;
}

size_t Scene::triangleCount() const {
  size_t n = 0;
  for (auto& m : meshes) n += m.triangles.size();
  return n;
}

namespace {
Bounds meshBounds(const std::vector<Mesh>& meshes, float time, bool dynamicOnly) {
  Bounds b;
  for (auto& m : meshes) {
    if (dynamicOnly && !m.dynamic) continue;
    glm::mat4 M = m.objectToWorld(time);
    for (auto& p : m.positions) b.extend(glm::vec3(M * glm::vec4(p, 1.0f)));
  }
  return b;
}
}  // namespace

Bounds Scene::bounds(float time) const { return meshBounds(meshes, time, false); }

Bounds Scene::dynamicBounds(float time) const { return meshBounds(meshes, time, true); }

Scene Scene::meshGeometry(bool dynamic) const {
  Scene out;
  out.name = name;
  for (const Mesh& m : meshes)
    if (m.dynamic == dynamic) out.meshes.push_back(m);
  out.materials = materials;
  for (Material& m : out.materials) m.albedoTexture = -1;
  out.lights = lights;
  out.environment.color = environment.color;
  out.environment.scale = environment.scale;
  out.camera = camera;
  out.cameraPath = cameraPath;
  out.twoSidedEmission = twoSidedEmission;
  return out;
}

bool Scene::hasDynamicMeshes() const {
  for (auto& m : meshes)
    if (m.dynamic) return true;
  return false;
}

glm::vec3 Scene::environmentRadiance(glm::vec3 dir) const {
  if (environment.mapTexture < 0) return environment.color;
  glm::vec2 uv = shared::latLongUv(dir);
  return textures[environment.mapTexture].lookup(uv, false) * environment.scale;
}

FlatScene flatten(const Scene& scene, float time) {
  FlatScene f;
  size_t n = scene.triangleCount();
  f.positions.reserve(3 * n);
  f.normals.reserve(3 * n);
  f.uvs.reserve(3 * n);
  f.material.reserve(n);
  f.meshOfTriangle.reserve(n);
  for (size_t mi = 0; mi < scene.meshes.size(); ++mi) flattenMesh(scene, int(mi), time, f);
  return f;
}

void flattenMesh(const Scene& scene, int mi, float time, FlatScene& f) {
  const Mesh& m = scene.meshes[size_t(mi)];
  glm::mat4 M = m.objectToWorld(time);
  glm::mat3 N = glm::transpose(glm::inverse(glm::mat3(M)));
  // Each vertex transformed once (a vertex is shared by ~6 corners), then gathered per corner.
  std::vector<glm::vec3> wp(m.positions.size()), wn(m.normals.size());
  for (size_t v = 0; v < wp.size(); ++v) wp[v] = glm::vec3(M * glm::vec4(m.positions[v], 1.0f));
  for (size_t v = 0; v < wn.size(); ++v) wn[v] = glm::normalize(N * m.normals[v]);
  for (auto& t : m.triangles) {
    const glm::vec3 p[3] = {wp[t[0]], wp[t[1]], wp[t[2]]};
    glm::vec3 ng = glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
    for (int k = 0; k < 3; ++k) {
      f.positions.push_back(p[k]);
      glm::vec3 n = wn.empty() ? ng : wn[t[k]];
      if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) n = ng;
      f.normals.push_back(n);
      f.uvs.push_back(m.uvs.empty() ? glm::vec2(0.0f) : m.uvs[t[k]]);
    }
    f.material.push_back(m.material);
    f.meshOfTriangle.push_back(mi);
  }
}

const char* lightTypeName(LightType t) {
  return t == LightType::Point ? "point" : t == LightType::Spot ? "spot" : "directional";
}

}  // namespace vgi
