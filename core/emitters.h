// Area lights: the emissive triangles of a scene at one instant (every mesh
// whose material has emission), with the sampling both renderer families use.
//
// Emission is constant radiance Le over a triangle. One-sided emitters (the
// default, as pbrt-v4 and Mitsuba 3) emit on the side their winding's normal
// (right-hand rule, counter-clockwise seen from the front) points to; a scene
// with "two_sided_emission": true emits from both sides (MTL's Ke has no side).
//
// The CPU reference samples a point by `sample()` (triangle chosen in
// proportion to its power, then uniform on it) for next-event estimation with
// MIS; the GL methods turn one such point per sample into a cosine spot light
// of intensity Le·A/p (`spotLights()`), rendered with its light map like any
// spot, so over `--spp` samples they converge to the area light's direct light
// and soft shadows.
#pragma once
#include <vector>

#include "core/scene.h"
#include "shaders/shared/emitters.glsl"

namespace vgi {

struct EmitterTriangle {
  glm::vec3 p0, e1, e2;  // p0 + u·e1 + v·e2
  glm::vec3 normal;      // unit, the winding's front side
  float area = 0;
  glm::vec3 radiance{0.0f};
  int mesh = -1;
  int flatTriangle = -1;  // index in the FlatScene it came from
};

struct EmitterSample {
  glm::vec3 p, normal;  // the point and its emitter's front normal
  glm::vec3 radiance;   // Le
  float pdfArea = 0;    // of choosing this point, per unit area (selection included)
  int emitter = -1;
};

class Emitters {
 public:
  Emitters() = default;
  // From the emissive triangles of `flat` (a flattening of `scene`).
  Emitters(const Scene& scene, const FlatScene& flat);
  // Flattens only the emissive meshes of `scene` at `time`.
  static Emitters ofScene(const Scene& scene, float time);

  bool empty() const { return triangles_.empty(); }
  size_t size() const { return triangles_.size(); }
  bool twoSided() const { return twoSided_; }
  const std::vector<EmitterTriangle>& triangles() const { return triangles_; }

  // A point by u ∈ [0,1)²: u.x picks the triangle by power and is reused
  // (rescaled) with u.y for the point, so a stratified u covers every emitter.
  EmitterSample sample(glm::vec2 u) const;
  // The area density sample() gives to points of emitter `e`.
  float pdfArea(int e) const;
  // Emitter index of flat triangle t, or −1.
  int emitterOfTriangle(size_t t) const { return t < emitterOf_.size() ? emitterOf_[t] : -1; }
  // The same for every triangle of the flattening it was made from.
  const std::vector<int>& emitterOfTriangles() const { return emitterOf_; }
  // The rows the GL device samples (shaders/shared/emitters.glsl), in emitter order.
  std::vector<shared::PackedEmitter> packed() const;
  // Le leaving emitter `e` along `w` (unit, pointing away from it): 0 behind a one-sided emitter.
  glm::vec3 radianceToward(int e, glm::vec3 w) const;
  // Power radiated by emitter `e`, π·Le·A per emitting side (W per RGB channel).
  glm::vec3 power(size_t e) const;

  // The spot lights (cone 90°, falloff cos θ, intensity Le·A/p; two opposite
  // ones for a two-sided emitter) of the point sample(u).
  std::vector<Light> spotLights(glm::vec2 u) const;

 private:
  std::vector<EmitterTriangle> triangles_;
  std::vector<float> cdf_;  // by luminance power, cdf_.back() == 1
  std::vector<int> emitterOf_;
  bool twoSided_ = false;
};

// The u of sample k of a run with `seed`: Roberts' R2 sequence (the plastic
// number's additive recurrence, low-discrepancy at every count, unrelated to
// the Halton sequences of the camera jitter and the gather rotations),
// Cranley–Patterson rotated by the seed.
glm::vec2 emitterSequence(int k, uint32_t seed);

}  // namespace vgi
