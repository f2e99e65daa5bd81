// The ray population of near-field gathering (VGI §5.1), for benchmarks and
// accuracy studies: points sampled uniformly by area on the scene's triangles,
// each shooting one cosine-distributed ray about its normal (the side facing
// the camera), started `offset` world units off the surface, of length tmax.
// Seeded: the same rays for every tracer.
#pragma once
#include <cstdint>
#include <vector>

#include "core/scene.h"
#include "traverse/ray_tracers.h"

namespace vgi {

struct RayPopulation {
  size_t count = 1000000;
  uint32_t seed = 1;
  float tmax = 0.0f;          // world units (may be +inf)
  float offset = 0.0f;        // world units along the normal
  glm::vec3 viewpoint{0.0f};  // normals are flipped to face it
};

// Throws if the scene has no triangle with a positive area.
std::vector<TraceRay> surfaceRays(const FlatScene& scene, const RayPopulation& population);

}  // namespace vgi
