layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
uniform mat4 uViewProj;
out vec3 vPosition;
out vec3 vNormal;
out vec2 vUv;
void main() {
  vPosition = inPosition;
  vNormal = inNormal;
  vUv = inUv;
  gl_Position = uViewProj * vec4(inPosition, 1.0f);
}
