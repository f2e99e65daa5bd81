// The grid as the GL voxelizers receive it (set by setGridUniforms in
// voxelize/gpu_grid.cpp).
#include "shared/voxel_grid.glsl"
uniform vec4 uOrigin;
uniform vec4 uAxisX;
uniform vec4 uAxisY;
uniform vec4 uAxisZ;
uniform uvec4 uResolution;
GridParams gridFromUniforms() {
  GridParams g;
  g.origin = uOrigin;
  g.axisX = uAxisX;
  g.axisY = uAxisY;
  g.axisZ = uAxisZ;
  g.resolution = uResolution;
  return g;
}
