// Multi-valued grids on the CPU: per cell the number of atlas points and the
// mean of each requested channel (normal, albedo, glossy = ks rgb + exponent),
// decoded from the GPU's fixed-point sums (shaders/shared/value_grid.glsl).
#pragma once
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "voxelize/voxel_grid.h"

namespace vgi {

// The channels a multi-valued voxelization can build, in a fixed order.
const std::vector<std::string>& valueChannelNames();
// Index of a channel in valueChannelNames() (= shared::VALUE_CHANNEL_*); throws if unknown.
uint32_t valueChannelIndex(const std::string& channel);
// "normal,albedo" → validated list (throws naming the bad entry).
std::vector<std::string> parseValueChannels(const std::string& list);

struct ValueGrids {
  GridBox box;
  std::vector<uint32_t> counts;               // points per cell (x fastest)
  std::vector<std::string> channels;          // built channels
  std::vector<std::vector<glm::vec4>> means;  // per channel, per cell (0 where count = 0)

  size_t cellIndex(uint32_t x, uint32_t y, uint32_t z) const {
    return (size_t(z) * box.resolution.y + y) * box.resolution.x + x;
  }
  const std::vector<glm::vec4>& channel(const std::string& name) const;  // throws if not built
  nlohmann::json summary() const;  // per channel: cells with values, mean of the means
};

// Decodes sums (4 uints per cell) for a channel: lo/hi per component.
// radianceMax: the radiance sums' fixed-point range (AtlasVoxelizer::insertRadiance).
std::vector<glm::vec4> decodeMeans(const std::vector<uint32_t>& sums, const std::vector<uint32_t>& counts,
                                   const std::string& channel, float radianceMax = 0.0f);

// Picture of a channel: per column (looking along depth), the value of the first cell with points.
void writeValuePicture(const ValueGrids& grids, const std::string& channel, const std::string& path);

}  // namespace vgi
