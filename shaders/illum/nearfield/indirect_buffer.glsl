// What the near-field passes share about the indirect buffer: the
// full-resolution G-buffer, the scale (image pixels per indirect pixel), the
// representative image texel of each indirect pixel, and the geometry-aware
// weights of the blur and the upsampling — a neighbour counts when its surface
// lies on the receiver's tangent plane (distance along the receiver's normal,
// relative to the world size of a pixel there) and faces the same way.
#include "../../shared/gbuffer.glsl"
layout(binding = TEXUNIT_GBUFFER_POSITION) uniform sampler2D gPosition;
layout(binding = TEXUNIT_GBUFFER_NORMAL) uniform sampler2D gNormal;
uniform int uScale;  // 1, 2 or 4

// The image texel an indirect pixel stands for.
ivec2 representative(ivec2 q, ivec2 full) { return min(q * uScale + uScale / 2, full - 1); }

uniform vec3 uCameraPosition;
uniform float uPixelAngle;   // world size of one full-resolution pixel per unit distance

float geometryWeight(vec3 p, vec3 n, vec3 pj, vec3 nj, float pixels) {
  float plane = abs(dot(pj - p, n));
  float scale = uPixelAngle * distance(p, uCameraPosition) * pixels;
  float wn = max(dot(n, nj), 0.0f);
  wn *= wn;
  wn *= wn;  // cos⁴
  float wp = exp(-(plane * plane) / max(scale * scale, 1e-30f));
  return wn * wp;
}
