// Geometry-aware weights of the blur and the upsampling: a neighbour counts
// when its surface lies on the receiver's tangent plane (distance along the
// receiver's normal, relative to the world size of a pixel there) and faces
// the same way.
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
