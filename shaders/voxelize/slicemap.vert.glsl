// Single-pass slicemap voxelization (Eisemann & Décoret, "Fast Scene
// Voxelization and Applications", I3D 2006): an orthographic view of the grid
// box along its depth axis; each fragment sets the bit of its depth cell.
#include "grid_uniforms.glsl"
layout(location = 0) in vec3 inPosition;
out float vDepth;  // grid z (cells)
void main() {
  vec3 q = worldToGrid(gridFromUniforms(), inPosition);
  vDepth = q.z;
  vec3 ndc = q / vec3(uResolution.xyz) * 2.0f - 1.0f;
  // Keep every depth: cells outside the grid are rejected per fragment.
  gl_Position = vec4(ndc.x, ndc.y, 0.0f, 1.0f);
}
