in vec3 vPosition;
flat in int vTriangle;
layout(location = 0) out vec4 outPosition;  // w = 1: valid texel
layout(location = 1) out int outTriangle;
void main() {
  outPosition = vec4(vPosition, 1.0f);
  outTriangle = vTriangle;
}
