#include "core/emitters.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "shaders/shared/emitters.glsl"
#include "shaders/shared/sampling.glsl"

namespace vgi {

namespace {
float luminance(glm::vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }
}  // namespace

Emitters::Emitters(const Scene& scene, const FlatScene& flat) : twoSided_(scene.twoSidedEmission) {
  emitterOf_.assign(flat.triangleCount(), -1);
  double total = 0;
  std::vector<double> power;
  for (size_t t = 0; t < flat.triangleCount(); ++t) {
    const Material& m = scene.materials[size_t(flat.material[t])];
    if (m.emission == glm::vec3(0.0f)) continue;
    EmitterTriangle e;
    e.p0 = flat.positions[3 * t];
    e.e1 = flat.positions[3 * t + 1] - e.p0;
    e.e2 = flat.positions[3 * t + 2] - e.p0;
    glm::vec3 c = glm::cross(e.e1, e.e2);
    e.area = 0.5f * glm::length(c);
    if (!(e.area > 0.0f) || !std::isfinite(e.area)) continue;  // degenerate: emits nothing
    e.normal = c / (2.0f * e.area);
    e.radiance = m.emission;
    e.mesh = flat.meshOfTriangle.empty() ? -1 : flat.meshOfTriangle[t];
    e.flatTriangle = int(t);
    emitterOf_[t] = int(triangles_.size());
    triangles_.push_back(e);
    // A grey-less emitter (luminance 0 but some channel > 0) still gets chosen.
    double p =
        std::max(double(luminance(m.emission)), 1e-6 * double(m.emission.x + m.emission.y + m.emission.z)) *
        double(e.area);
    power.push_back(p);
    total += p;
  }
  double acc = 0;
  for (double p : power) {
    acc += p;
    cdf_.push_back(float(acc / total));
  }
  if (!cdf_.empty()) cdf_.back() = 1.0f;
}

Emitters Emitters::ofScene(const Scene& scene, float time) {
  FlatScene flat;
  for (size_t mi = 0; mi < scene.meshes.size(); ++mi) {
    const Mesh& m = scene.meshes[mi];
    if (scene.materials[size_t(m.material)].emission != glm::vec3(0.0f))
      flattenMesh(scene, int(mi), time, flat);
  }
  return Emitters(scene, flat);
}

float Emitters::pdfArea(int e) const {
  const size_t i = size_t(e);
  const float p = cdf_[i] - (i == 0 ? 0.0f : cdf_[i - 1]);
  return p / triangles_[i].area;
}

EmitterSample Emitters::sample(glm::vec2 u) const {
  VGI_CHECK(!empty());
  const size_t i = size_t(std::lower_bound(cdf_.begin(), cdf_.end(), u.x) - cdf_.begin());
  const size_t e = std::min(i, triangles_.size() - 1);
  const float lo = e == 0 ? 0.0f : cdf_[e - 1], width = cdf_[e] - lo;
  const EmitterTriangle& t = triangles_[e];
  EmitterSample s;
  s.p = shared::uniformTrianglePoint(t.p0, t.e1, t.e2, shared::emitterRescale(u.x, lo, width), u.y);
  s.normal = t.normal;
  s.radiance = t.radiance;
  s.pdfArea = width / t.area;
  s.emitter = int(e);
  return s;
}

glm::vec3 Emitters::radianceToward(int e, glm::vec3 w) const {
  const EmitterTriangle& t = triangles_[size_t(e)];
  return shared::emitterRadianceToward(t.normal, t.radiance, twoSided_, w);
}

std::vector<shared::PackedEmitter> Emitters::packed() const {
  std::vector<shared::PackedEmitter> rows;
  for (size_t i = 0; i < triangles_.size(); ++i) {
    const EmitterTriangle& t = triangles_[i];
    shared::PackedEmitter r;
    r.p0Cdf = glm::vec4(t.p0, cdf_[i]);
    r.e1CdfLo = glm::vec4(t.e1, i == 0 ? 0.0f : cdf_[i - 1]);
    r.e2Area = glm::vec4(t.e2, t.area);
    r.normalSides = glm::vec4(t.normal, twoSided_ ? 1.0f : 0.0f);
    r.radiance = glm::vec4(t.radiance, 0.0f);
    rows.push_back(r);
  }
  return rows;
}

glm::vec3 Emitters::power(size_t e) const {
  const EmitterTriangle& t = triangles_[e];
  return float(M_PI) * t.radiance * t.area * (twoSided_ ? 2.0f : 1.0f);
}

std::vector<Light> Emitters::spotLights(glm::vec2 u) const {
  std::vector<Light> out;
  if (empty()) return out;
  EmitterSample s = sample(u);
  Light l;
  l.type = LightType::Spot;
  l.position = s.p;
  l.direction = s.normal;
  l.intensity = s.radiance / s.pdfArea;  // Le·A/p: I(θ) = Le·A/p·cos θ
  l.coneHalfAngleDeg = 90.0f;
  l.falloff = 1.0f;
  out.push_back(l);
  if (twoSided_) {
    l.direction = -s.normal;
    out.push_back(l);
  }
  return out;
}

glm::vec2 emitterSequence(int k, uint32_t seed) {
  // R2, rotated by two hashes of the seed (shaders/shared/sampling.glsl).
  return shared::r2Point(uint32_t(k), shared::pcgHash(seed * 2u + 1u), shared::pcgHash(seed * 2u + 2u));
}

}  // namespace vgi
