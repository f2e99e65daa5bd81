#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace vgi {

struct Chart {
  std::vector<uint32_t> faces;  // triangle indices
  glm::vec3 normal{0, 0, 1};    // area-weighted mean normal
  bool planar = false;          // every face within planar_deg of the seed's normal
};

struct SegmentationOptions {
  float maxNormalDeviationDeg = 40.0f;  // from the seed's and from the chart's mean normal
  float planarDeviationDeg = 1.0f;
  size_t maxFaces = 4096;  // keeps per-chart solves small and charts packable
};

struct Segmentation {
  std::vector<Chart> charts;
  long facesSplitOff = 0;  // faces OpenMesh refused (non-manifold): added with their own vertices
};

// Region growing over the half-edge structure: seeds in order of decreasing
// area, grown across edges to faces whose normal stays within the bound.
// Every triangle ends in exactly one chart (degenerate ones in their own).
Segmentation segmentCharts(const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& triangles,
                           const SegmentationOptions& options);

}  // namespace vgi
