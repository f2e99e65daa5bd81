layout(location = 0) in vec3 inPosition;
uniform mat4 uViewProj;
out vec3 vPosition;
void main() {
  vPosition = inPosition;
  gl_Position = uViewProj * vec4(inPosition, 1.0f);
}
