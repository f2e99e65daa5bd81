// The voxelizers behind `vgi voxelize`, in an explicit table.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/profiler.h"
#include "voxelize/voxel_grid.h"

namespace vgi {

class GlContext;
class ShaderLibrary;

struct VoxelizeRequest {
  const Scene* scene = nullptr;
  GridBox box;
  float time = 0;
  int threads = 0;
  GlContext* gl = nullptr;           // for GL voxelizers
  ShaderLibrary* shaders = nullptr;  // idem
  // Atlas voxelizer: texel = smallest voxel edge / texelsPerVoxel, unless a
  // manual atlasResolution (per mesh, square) is given.
  float texelsPerVoxel = 2.0f;
  int atlasResolution = 0;
  std::string atlasCacheDir;
};

struct VoxelizerInfo {
  std::string name, description;
  bool needsGl;
  // Fills `stats` with what it measured (e.g. "points", "atlas_resolution").
  std::function<BinaryGrid(const VoxelizeRequest&, Profiler&, nlohmann::json& stats)> run;
};

const std::vector<VoxelizerInfo>& voxelizerRegistry();
const VoxelizerInfo& findVoxelizer(const std::string& name);  // throws listing the names

}  // namespace vgi
