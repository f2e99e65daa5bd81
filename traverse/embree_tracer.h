// Exact ray–triangle queries with Embree (robust mode): the ground truth that
// the voxel tracers and every approximate module are measured against.
#pragma once
#include <glm/glm.hpp>
#include <string>

#include "core/scene.h"

struct RTCDeviceTy;
struct RTCSceneTy;

namespace vgi {

struct TriangleHit {
  bool hit = false;
  float t = 0;
  int triangle = -1;
  float u = 0, v = 0;  // barycentrics of vertices 1 and 2
};

class EmbreeTracer {
 public:
  // Keeps no reference to `scene` after construction.
  explicit EmbreeTracer(const FlatScene& scene);
  ~EmbreeTracer();
  EmbreeTracer(const EmbreeTracer&) = delete;
  EmbreeTracer& operator=(const EmbreeTracer&) = delete;

  // Thread-safe. dir need not be normalised; t is in units of |dir|.
  TriangleHit firstHit(glm::vec3 origin, glm::vec3 dir, float tnear, float tfar) const;
  bool occluded(glm::vec3 origin, glm::vec3 dir, float tnear, float tfar) const;

 private:
  RTCDeviceTy* device_ = nullptr;
  RTCSceneTy* scene_ = nullptr;
  std::string error_;  // set by Embree's error callback during construction
};

}  // namespace vgi
