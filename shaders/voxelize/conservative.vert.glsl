#include "grid_uniforms.glsl"
layout(location = 0) in vec3 inPosition;
out vec3 vGrid;
#ifdef CONSERVATIVE_VALUES
// Passes that store values per cell (avg's grid) get the world position and uv too.
layout(location = 2) in vec2 inUv;
out vec3 vWorld;
out vec2 vUv;
#endif
void main() {
  vGrid = worldToGrid(gridFromUniforms(), inPosition);
#ifdef CONSERVATIVE_VALUES
  vWorld = inPosition;
  vUv = inUv;
#endif
  gl_Position = vec4(0.0f, 0.0f, 0.0f, 1.0f);  // placed by the geometry shader
}
