// GPU side of a binary grid: the word SSBO the GL voxelizers OR into (laid out
// like BinaryGrid, so a read-back is a plain copy) and the grid uniforms their
// shaders declare (uOrigin, uAxisX/Y/Z, uResolution).
#pragma once
#include <functional>
#include <string>

#include "voxelize/voxel_grid.h"

namespace vgi {
class ShaderLibrary;

void setGridUniforms(ShaderLibrary& shaders, unsigned program, const GridBox& box);

// Runs `draw` into a framebuffer without attachments of the given size, depth
// test and culling off: for voxelizers whose fragments only write SSBOs.
void drawWithoutAttachments(int width, int height, const std::function<void()>& draw);

struct VoxelizeRequest;
class Profiler;

// Draws every triangle of the request's scene (at its time) once with `program`
// into an attachment-less width×height framebuffer whose fragments OR bits into
// a fresh grid (SSBO binding 0); the grid uniforms are set. Passes: "upload",
// `passName`, "readback".
BinaryGrid rasterizeSceneIntoGrid(const VoxelizeRequest& request, unsigned program, int width, int height,
                                  const std::string& passName, Profiler& profiler);

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
