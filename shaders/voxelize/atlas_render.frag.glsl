// Atlas texels: world position (w = 1: valid) and the triangle that wrote it.
// Edge fragments (uClampToTriangle) are interpolated at their centre's
// projection on the line, which overshoots the edge's ends by up to half a
// texel: they are pulled back onto their triangle, so every point lies on the
// surface.
#include "../shared/closest_point.glsl"
in vec3 vPosition;
flat in int vTriangle;
uniform mat4 uModel;
uniform int uClampToTriangle;
layout(std430, binding = 2) readonly buffer Corners { float corners[]; };  // the VBO: 6 floats per corner
layout(location = 0) out vec4 outPosition;
layout(location = 1) out int outTriangle;
vec3 corner(int i) {
  int o = 6 * i;
  return (uModel * vec4(corners[o], corners[o + 1], corners[o + 2], 1.0f)).xyz;
}
void main() {
  vec3 p = vPosition;
  if (uClampToTriangle != 0)
    p = closestPointOnTriangle(p, corner(3 * vTriangle), corner(3 * vTriangle + 1), corner(3 * vTriangle + 2));
  outPosition = vec4(p, 1.0f);
  outTriangle = vTriangle;
}
