// vgi view (apps/viewer.cpp): the accumulated image (rows top-down, as the
// film reads it back) scaled by the exposure and encoded as sRGB, the same
// curve as the PNGs `vgi render` writes (core/image.cpp).
#version 450 core
in vec2 vUv;
out vec4 oColor;
layout(binding = 0) uniform sampler2D uImage;
uniform float uExposure;
float srgb(float x) {
  x = clamp(x, 0.0, 1.0);
  return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}
void main() {
  const vec3 c = texture(uImage, vec2(vUv.x, 1.0 - vUv.y)).rgb * uExposure;
  oColor = vec4(srgb(c.r), srgb(c.g), srgb(c.b), 1.0);
}
