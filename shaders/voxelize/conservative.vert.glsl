#include "../shared/voxel_grid.glsl"
layout(location = 0) in vec3 inPosition;
uniform vec4 uOrigin;
uniform vec4 uAxisX;
uniform vec4 uAxisY;
uniform vec4 uAxisZ;
uniform uvec4 uResolution;
out vec3 vGrid;
void main() {
  GridParams g;
  g.origin = uOrigin;
  g.axisX = uAxisX;
  g.axisY = uAxisY;
  g.axisZ = uAxisZ;
  g.resolution = uResolution;
  vGrid = worldToGrid(g, inPosition);
  gl_Position = vec4(0.0f, 0.0f, 0.0f, 1.0f);  // placed by the geometry shader
}
