#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "voxelize/chart_segmentation.h"

namespace vgi {

// A flattened chart: 3 UVs per face, in world units (a unit of UV is a unit of
// surface length at the chart's nominal density).
struct FlatChart {
  std::vector<uint32_t> faces;
  std::vector<glm::vec2> uv;
  bool lscm = false;
  float maxStretch = 1;  // largest singular value of d(world)/d(uv) over its faces
};

// Planar projection for planar charts, least squares conformal maps otherwise
// (scaled so the UV area equals the surface area). A result with a flipped or
// overlapping triangle is split into connected halves and retried, down to
// single triangles, which are always valid.
std::vector<FlatChart> parametrizeChart(const std::vector<glm::vec3>& positions,
                                        const std::vector<glm::uvec3>& triangles, const Chart& chart);

// True when every face has positive UV area and no two faces that do not share
// an edge overlap (interiors, with a tolerance relative to the chart size).
bool chartIsValid(const std::vector<glm::uvec3>& triangles, const FlatChart& chart);

}  // namespace vgi
