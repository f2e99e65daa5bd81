// GPU side of a binary grid: the word SSBO the GL voxelizers OR into (laid out
// like BinaryGrid, so a read-back is a plain copy) and the grid uniforms their
// shaders declare (uOrigin, uAxisX/Y/Z, uResolution).
#pragma once
#include "voxelize/voxel_grid.h"

namespace vgi {

void setGridUniforms(unsigned program, const GridBox& box);

class GpuGridBuffer {
 public:
  explicit GpuGridBuffer(const GridBox& box);  // cleared to zero
  ~GpuGridBuffer();
  GpuGridBuffer(const GpuGridBuffer&) = delete;
  GpuGridBuffer& operator=(const GpuGridBuffer&) = delete;
  unsigned buffer() const { return buffer_; }
  size_t bytes() const { return bytes_; }
  void bind(unsigned binding) const;
  void read(BinaryGrid& grid) const;

 private:
  unsigned buffer_ = 0;
  size_t bytes_ = 0;
};

}  // namespace vgi
