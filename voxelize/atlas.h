// Per-mesh texture atlases for atlas voxelization (VGI §3): chart segmentation,
// parametrization and packing into a square atlas with gutters, at a texel
// density proportional to world area.
#pragma once
#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "voxelize/chart_segmentation.h"

namespace vgi {

struct AtlasOptions {
  float texelWorld = 0;  // world length of one texel; 0 = derive from `resolution`
  int resolution = 0;    // manual atlas resolution (square); 0 = follow texelWorld
  int gutter = 2;        // empty texels around every chart
  SegmentationOptions segmentation;
  std::string cacheDir;  // the set-up cache's folder (voxelize/setup_cache.h); "" = no cache
};

struct MeshAtlas {
  int resolution = 0;
  float texelWorld = 0;
  std::vector<glm::vec2> uv;  // 3 per triangle, in [0, 1]² (texel centres at (i + ½)/resolution)
  int charts = 0, lscmCharts = 0;
  long facesSplitOff = 0;
  double utilization = 0;  // chart area / atlas area
  float maxStretch = 1;    // largest world length per nominal texel length
  double ms = 0;
  bool fromCache = false;
  nlohmann::json toJson() const;
};

// texel = smallest voxel edge / texelsPerVoxel. Points are then at most
// texel·√2/2 from any surface point inside a chart (at unit stretch), so every
// voxel whose intersection with the surface contains a disk of that radius gets
// one; the default density and its derivation: grid_metrics.h, voxelizer.h.
float autoTexelWorld(glm::vec3 voxelSize, float texelsPerVoxel);

// `positions` in world space (density follows world area). Throws when the
// atlas would exceed maxResolution texels on a side.
MeshAtlas buildAtlas(const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& triangles,
                     const AtlasOptions& options, int maxResolution = 16384);

}  // namespace vgi
