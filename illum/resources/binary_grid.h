// Resource kind "binary_grid": the scene voxelized into a binary grid (bitmask
// columns, VGI §3) over a tight box that spans the animation's frames, by any
// voxelizer of voxelizerRegistry(). GL with voxelizer=atlas keeps the
// AtlasVoxelizer (static meshes once, each frame the dynamic ones inserted
// into a copy, VGI §3.2; its `values` channels accumulated by the same
// insertion, the value grids' source); the others give a BinaryGrid on the
// host. It offers the GridBox, and the AtlasVoxelizer or the BinaryGrid;
// methods read it through its OR-mip pyramid (illum/resources/or_mip_pyramid.h).
#pragma once
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "illum/framework/resources.h"
#include "voxelize/voxel_grid.h"
#include "voxelize/voxelizer.h"

namespace vgi {

class ParamSet;

struct BinaryGridNeed {
  static constexpr const char* kKind = "binary_grid";
  static const ResourceKind& row();  // its row of the kinds table (binaryGridKind())
  glm::uvec3 resolution{128};
  std::string voxelizer = "atlas";  // a name of voxelizerRegistry()
  // Cubic cells (cone tracing: a mip level's texel is a cube of 2^l cells):
  // the fitted box grows about its centre along the shorter axes.
  bool cubicCells = false;
  // Channels of valueChannelNames() the atlas insertion accumulates as well
  // (normal, albedo, glossy, radiance): what value grids over it can resolve.
  std::vector<std::string> values;
  // The voxelizers' own settings (VoxelizeRequest's; `vgi voxelize` options, the methods keep the defaults).
  float texelsPerVoxel = kAutoTexelsPerVoxel;  // atlas
  int atlasResolution = 0;                     // atlas: per mesh, 0 = from texelsPerVoxel
  float atlasFootprint = 1.0f;                 // atlas
  float hybridCutoff = 4.0f;                   // hybrid
  bool atlasCache = true;                      // atlas: read and write the atlas cache
  // Read and write a static scene's grid, with its value channels' sums, in the set-up cache
  // (voxelize/setup_cache.h, value_sums_cache.h): a second render of the scene skips the voxelization.
  // Not with the radiance channel (it follows the lights) nor in `vgi voxelize`, which measures the
  // voxelizer itself.
  bool gridCache = true;
  nlohmann::json key() const {
    return {{"resolution", {resolution.x, resolution.y, resolution.z}},
            {"voxelizer", voxelizer},
            {"cubic_cells", cubicCells},
            {"values", values},
            {"texels_per_voxel", texelsPerVoxel},
            {"atlas_resolution", atlasResolution},
            {"atlas_footprint", atlasFootprint},
            {"hybrid_cutoff", hybridCutoff},
            {"atlas_cache", atlasCache},
            {"grid_cache", gridCache}};
  }
};

// The `voxels` (N or WxHxD) and `voxelizer` parameters of a module that
// traces a binary grid; `grids`: how many grid-sized buffers it keeps (the
// memory check).
BinaryGridNeed readBinaryGridParams(ParamSet& params, int grids, bool atlasOnly = false,
                                    const std::string& defaultVoxelizer = "atlas");

ResourceKind binaryGridKind();

}  // namespace vgi
