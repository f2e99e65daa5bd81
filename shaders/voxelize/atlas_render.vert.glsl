// Atlas rendering (VGI §3.1): a mesh drawn in its texture-atlas space, writing
// the world position of every covered texel.
layout(location = 0) in vec3 inPosition;  // object space
layout(location = 1) in vec2 inAtlasUv;   // [0, 1]²
layout(location = 2) in float inTriangle;
uniform mat4 uModel;  // object → world at the frame's time
out vec3 vPosition;
flat out int vTriangle;
void main() {
  vPosition = (uModel * vec4(inPosition, 1.0f)).xyz;
  vTriangle = int(inTriangle);
  gl_Position = vec4(inAtlasUv * 2.0f - 1.0f, 0.0f, 1.0f);
}
