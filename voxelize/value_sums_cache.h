// A multi-valued insertion's sums in the set-up cache (voxelize/setup_cache.h): per cell the atlas
// points' count and, per channel (normal, albedo, glossy), a uvec4 of fixed-point sums — what
// ValueTextures::resolve reads (AtlasVoxelizer::valueBuffers). Packed sparsely, the occupied cells only
// (a grid is mostly empty: dense, 128³ with three channels would be 109 MB), and unpacked into GL
// buffers of the atlas voxelizer's own layout, so the value textures resolve from them unchanged and a
// second render of a scene skips the atlas raster and both insertions. The radiance channel is not kept:
// it follows the lights.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/gl_handles.h"
#include "voxelize/value_textures.h"

namespace vgi {

// Reads the sums of `cells` cells back from GL and packs them (needs a current context). Only the
// normal, albedo and glossy channels (sums[0..2]) are packed.
std::vector<uint8_t> packValueSums(const ValueSumBuffers& sums, size_t cells);

// The sums unpacked into GL buffers.
class CachedValueSums {
 public:
  // Null when `payload` is not a packing of `cells` cells with exactly the channels `channelMask`
  // (bit k: sums[k]) — the caller then builds anew.
  static std::unique_ptr<CachedValueSums> unpack(const uint8_t* payload, size_t bytes, size_t cells,
                                                 uint32_t channelMask);
  ValueSumBuffers buffers() const;
  double gpuBytes() const;

 private:
  size_t cells_ = 0;
  GlBuffer counts_;
  GlBuffer sums_[3];
};

// The channel mask of a list of channel names (normal, albedo, glossy; bit = the channel's index).
uint32_t valueChannelMask(const std::vector<std::string>& channels);

}  // namespace vgi
