// Atlas rendering (VGI §3.1): a mesh drawn in its texture-atlas space, writing
// the world position of every covered texel.
layout(location = 0) in vec3 inPosition;  // world space
layout(location = 1) in vec2 inAtlasUv;   // [0, 1]²
layout(location = 2) in float inTriangle;
out vec3 vPosition;
flat out int vTriangle;
void main() {
  vPosition = inPosition;
  vTriangle = int(inTriangle);
  gl_Position = vec4(inAtlasUv * 2.0f - 1.0f, 0.0f, 1.0f);
}
