// Every rasterised pass over the scene (G-buffer, light maps): world-space
// attributes, the triangle's geometric normal flat.
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec3 inGeometricNormal;
uniform mat4 uViewProj;
out vec3 vPosition;
out vec3 vNormal;
out vec2 vUv;
flat out vec3 vGeometricNormal;
void main() {
  vPosition = inPosition;
  vNormal = inNormal;
  vUv = inUv;
  vGeometricNormal = inGeometricNormal;
  gl_Position = uViewProj * vec4(inPosition, 1.0f);
}
