// Single-pass slicemap voxelization (Eisemann & Décoret, "Fast Scene
// Voxelization and Applications", I3D 2006): an orthographic view of the grid
// box along its depth axis; each fragment sets the bit of its depth cell.
#include "../shared/voxel_grid.glsl"
layout(location = 0) in vec3 inPosition;
uniform vec4 uOrigin;
uniform vec4 uAxisX;
uniform vec4 uAxisY;
uniform vec4 uAxisZ;
uniform uvec4 uResolution;
out float vDepth;  // grid z (cells)
void main() {
  GridParams g;
  g.origin = uOrigin;
  g.axisX = uAxisX;
  g.axisY = uAxisY;
  g.axisZ = uAxisZ;
  g.resolution = uResolution;
  vec3 q = worldToGrid(g, inPosition);
  vDepth = q.z;
  vec3 ndc = q / vec3(uResolution.xyz) * 2.0f - 1.0f;
  // Keep every depth: cells outside the grid are rejected per fragment.
  gl_Position = vec4(ndc.x, ndc.y, 0.0f, 1.0f);
}
