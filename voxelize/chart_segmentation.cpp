// Chart segmentation for the texture atlases of VGI §3 (Thiedemann et al.
// 2011; the paper assumes an atlas exists — we build our own, in the spirit of
// xatlas / Lévy et al. 2002 "Least Squares Conformal Maps", §5 segmentation):
// greedy region growing on the OpenMesh half-edge structure with a bound on
// the normal deviation, so each chart is close to a height field and can be
// flattened without folds.
//
// Non-manifold input gets faces of their own (voxelize/openmesh_build.h), so
// they still get UVs — no triangle is dropped.
#include "voxelize/chart_segmentation.h"

#include "voxelize/openmesh_build.h"

// GCC 12 reports a false -Wmaybe-uninitialized inside OpenMesh's property
// containers (vector<VectorT>::push_back); it is not in this file's code.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <algorithm>
#include <cmath>
#include <deque>
#include <numeric>

namespace vgi {

Segmentation segmentCharts(const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& tris,
                           const SegmentationOptions& opt) {
  Segmentation seg;
  OMesh mesh;
  std::vector<OMesh::FaceHandle> faceOf;
  seg.facesSplitOff = addTriangles(mesh, positions, tris, faceOf);
  std::vector<int> triOfFace;
  for (size_t t = 0; t < tris.size(); ++t) {
    const OMesh::FaceHandle fh = faceOf[t];
    if (fh.is_valid()) {
      if (triOfFace.size() <= size_t(fh.idx())) triOfFace.resize(size_t(fh.idx()) + 1, -1);
      triOfFace[size_t(fh.idx())] = int(t);
    }
  }

  std::vector<glm::vec3> normal(tris.size());
  std::vector<float> area(tris.size());
  for (size_t t = 0; t < tris.size(); ++t) {
    glm::vec3 c = glm::cross(positions[tris[t][1]] - positions[tris[t][0]],
                             positions[tris[t][2]] - positions[tris[t][0]]);
    float l = glm::length(c);
    area[t] = 0.5f * l;
    normal[t] = l > 0 ? c / l : glm::vec3(0, 0, 1);
  }
  std::vector<uint32_t> order(tris.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return area[a] > area[b]; });

  const float cosMax = std::cos(glm::radians(opt.maxNormalDeviationDeg));
  const float cosPlanar = std::cos(glm::radians(opt.planarDeviationDeg));
  std::vector<int> chartOf(tris.size(), -1);
  for (uint32_t seed : order) {
    if (chartOf[seed] >= 0) continue;
    Chart chart;
    const int id = int(seg.charts.size());
    const glm::vec3 seedN = normal[seed];
    glm::vec3 sum(0.0f);
    bool planar = true;
    std::deque<uint32_t> queue{seed};
    chartOf[seed] = id;
    while (!queue.empty() && chart.faces.size() < opt.maxFaces) {
      uint32_t t = queue.front();
      queue.pop_front();
      chart.faces.push_back(t);
      sum += area[t] * normal[t];
      planar = planar && glm::dot(normal[t], seedN) >= cosPlanar;
      glm::vec3 mean = glm::length(sum) > 0 ? glm::normalize(sum) : seedN;
      if (!faceOf[t].is_valid() || area[t] <= 0) continue;
      for (auto ff = mesh.ff_iter(faceOf[t]); ff.is_valid(); ++ff) {
        int n = size_t(ff->idx()) < triOfFace.size() ? triOfFace[size_t(ff->idx())] : -1;
        if (n < 0 || chartOf[size_t(n)] >= 0 || area[size_t(n)] <= 0) continue;
        if (glm::dot(normal[size_t(n)], seedN) < cosMax || glm::dot(normal[size_t(n)], mean) < cosMax)
          continue;
        chartOf[size_t(n)] = id;
        queue.push_back(uint32_t(n));
      }
    }
    for (uint32_t t : queue) chartOf[t] = -1;  // not taken: size limit reached
    chart.normal = glm::length(sum) > 0 ? glm::normalize(sum) : seedN;
    chart.planar = planar;
    seg.charts.push_back(std::move(chart));
  }
  return seg;
}

}  // namespace vgi
#pragma GCC diagnostic pop
