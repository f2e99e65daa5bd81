#include "traverse/ray_population.h"

#include <algorithm>
#include <random>

#include "core/error.h"
#include "shaders/shared/sampling.glsl"

namespace vgi {

std::vector<TraceRay> surfaceRays(const FlatScene& scene, const RayPopulation& pop) {
  const size_t n = scene.triangleCount();
  std::vector<double> cdf(n);
  double total = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3* p = &scene.positions[3 * i];
    double a = 0.5 * glm::length(glm::cross(glm::dvec3(p[1] - p[0]), glm::dvec3(p[2] - p[0])));
    total += std::isfinite(a) ? a : 0.0;
    cdf[i] = total;
  }
  if (!(total > 0.0)) fail("ray population: the scene has no triangle with a positive area");
  std::mt19937_64 rng(pop.seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::vector<TraceRay> rays(pop.count);
  for (TraceRay& r : rays) {
    size_t tri = size_t(std::upper_bound(cdf.begin(), cdf.end(), u01(rng) * total) - cdf.begin());
    tri = std::min(tri, n - 1);
    while (tri > 0 && cdf[tri] == cdf[tri - 1]) --tri;  // never a zero-area triangle
    const glm::vec3* p = &scene.positions[3 * tri];
    double su = std::sqrt(u01(rng)), v = u01(rng);
    glm::vec3 x = glm::vec3(glm::dvec3(p[0]) * (1.0 - su) + glm::dvec3(p[1]) * (su * (1.0 - v)) +
                            glm::dvec3(p[2]) * (su * v));
    glm::vec3 nrm = glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
    if (glm::dot(nrm, pop.viewpoint - x) < 0.0f) nrm = -nrm;
    glm::vec3 local = shared::cosineSampleHemisphere(glm::vec2(float(u01(rng)), float(u01(rng))));
    r.dir = glm::normalize(shared::basisToWorld(shared::makeBasis(nrm), local));
    r.origin = x + pop.offset * nrm;
    r.tmax = pop.tmax;
  }
  return rays;
}

}  // namespace vgi
