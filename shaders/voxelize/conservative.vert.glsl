#include "grid_uniforms.glsl"
layout(location = 0) in vec3 inPosition;
out vec3 vGrid;
void main() {
  vGrid = worldToGrid(gridFromUniforms(), inPosition);
  gl_Position = vec4(0.0f, 0.0f, 0.0f, 1.0f);  // placed by the geometry shader
}
