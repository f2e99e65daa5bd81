// The voxelizers behind `vgi voxelize`, in an explicit table.
#pragma once
#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "core/profiler.h"
#include "voxelize/voxel_grid.h"

namespace vgi {

class GlContext;
class ShaderLibrary;

constexpr float kAutoTexelsPerVoxel = 2.8284271f;  // 2√2

struct VoxelizeRequest {
  const Scene* scene = nullptr;
  GridBox box;
  float time = 0;
  int threads = 0;
  GlContext* gl = nullptr;           // for GL voxelizers
  ShaderLibrary* shaders = nullptr;  // idem
  // Atlas voxelizer: texel = smallest voxel edge / texelsPerVoxel, unless a
  // manual atlasResolution (per mesh, square) is given. The default 2√2 is the
  // rule of grid_metrics.h: every cell a planar surface crosses with a disk of
  // radius ¼ cell gets a point.
  float texelsPerVoxel = kAutoTexelsPerVoxel;
  int atlasResolution = 0;
  // Atlas voxelizer: each point also sets the cells within this many texels
  // that its triangle overlaps (shaders/shared/atlas_footprint.glsl); 0 = the
  // paper's single point per texel.
  float atlasFootprint = 1.0f;
  std::string atlasCacheDir;
  // Multi-valued grids to build as well (atlas voxelizer): "normal", "albedo",
  // "glossy", "radiance" (AtlasVoxelizer::insertRadiance). Only these are built.
  std::vector<std::string> valueGrids;
  // Hybrid voxelizer: triangles projected on their dominant plane smaller than
  // this (cells²) are voxelized triangle-parallel.
  float hybridCutoff = 4.0f;
};

struct VoxelizerInfo {
  std::string name, description;
  bool needsGl;
  // Every triangle sets its cells by itself: a scene's grid is the OR of its meshes' grids, so an
  // animation keeps the static meshes' grid and voxelizes only the dynamic ones again.
  bool perTriangle;
  // Fills `stats` with what it measured (e.g. "points", "atlas_resolution").
  std::function<BinaryGrid(const VoxelizeRequest&, Profiler&, nlohmann::json& stats)> run;
};

const std::vector<VoxelizerInfo>& voxelizerRegistry();
const VoxelizerInfo& findVoxelizer(const std::string& name);  // throws listing the names

}  // namespace vgi
