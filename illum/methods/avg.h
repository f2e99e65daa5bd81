// `avg`: instant radiosity with Approximate Visibility Grids (Bashford-Rogers
// et al. 2012; see avg.cpp), and the grid itself.
#pragma once
#include <memory>
#include <vector>

#include "core/gl_handles.h"
#include "illum/framework/method.h"
#include "voxelize/voxel_grid.h"

namespace vgi {

class GpuScene;
class ShaderLibrary;

// The approximate visibility grid over `box` (shaders/shared/avg.glsl):
// per cell the fixed-point sums of the unit normals and albedos of the
// triangles overlapping it and their count, rebuilt by build() from the scene
// as `gpu` holds it, by rasterization (three-axis conservative, each cell
// confirmed by the triangle–box test).
class AvgGrid {
 public:
  AvgGrid(const GridBox& box, ShaderLibrary& shaders);
  void build(const GpuScene& gpu);
  void bind() const;  // at BINDING_AVG
  const GridBox& box() const { return box_; }
  std::vector<uint32_t> read() const;  // 8 words per cell (avg.glsl)

 private:
  GridBox box_;
  ShaderLibrary& shaders_;
  GlBuffer cells_;
  unsigned prog_ = 0;
};

// The registry row: name, description, factory, exact counterpart.
MethodInfo avgMethod();

}  // namespace vgi
