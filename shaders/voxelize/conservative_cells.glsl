// The fragment half of the three-axis conservative rasterization (shared by
// the conservative voxelizer and `avg`'s grid): the cells of this pixel's
// column (along the dominant axis) within the triangle's depth range over the
// pixel, each confirmed by the shared triangle–box test, so over-conservative
// fragments of the expanded triangle visit nothing. The triangle and axis come
// from conservative.geom.glsl.
#include "shared/triangle_box.glsl"
flat in int gAxis;
flat in vec3 gA;
flat in vec3 gB;
flat in vec3 gC;
uniform uvec4 uResolution;
void visitCell(uvec3 cell);  // defined by the including shader

vec3 unswizzle(vec3 s, int axis) {
  if (axis == 0) return vec3(s.z, s.x, s.y);
  if (axis == 1) return vec3(s.y, s.z, s.x);
  return s;
}
float along(vec3 p, int axis) { return axis == 0 ? p.x : (axis == 1 ? p.y : p.z); }

// Calls visitCell(cell) for every cell of
// this fragment's column that the triangle (gA, gB, gC, grid coordinates) overlaps.
void visitTriangleCells() {
  vec2 pix = floor(gl_FragCoord.xy);
  vec3 res = vec3(uResolution.xyz);
  vec3 sres = gAxis == 0 ? vec3(res.y, res.z, res.x) : (gAxis == 1 ? vec3(res.z, res.x, res.y) : res);
  if (pix.x >= sres.x || pix.y >= sres.y) return;
  // Depth of the triangle's plane over the pixel square (w along the dominant axis).
  vec3 n = cross(gB - gA, gC - gA);
  float nw = along(n, gAxis);
  vec3 sn = gAxis == 0 ? vec3(n.y, n.z, n.x) : (gAxis == 1 ? vec3(n.z, n.x, n.y) : n);
  vec3 sa = gAxis == 0 ? vec3(gA.y, gA.z, gA.x) : (gAxis == 1 ? vec3(gA.z, gA.x, gA.y) : gA);
  float wmin = 1e30f, wmax = -1e30f;
  for (int i = 0; i < 4; ++i) {
    vec2 corner = pix + vec2(float(i & 1), float(i >> 1));
    float w = sa.z - (sn.x * (corner.x - sa.x) + sn.y * (corner.y - sa.y)) / nw;
    wmin = min(wmin, w);
    wmax = max(wmax, w);
  }
  float tmin = min(along(gA, gAxis), min(along(gB, gAxis), along(gC, gAxis)));
  float tmax = max(along(gA, gAxis), max(along(gB, gAxis), along(gC, gAxis)));
  wmin = max(wmin, tmin);
  wmax = min(wmax, tmax);
  int k0 = max(int(ceil(wmin)) - 1, 0), k1 = min(int(floor(wmax)), int(sres.z) - 1);
  for (int k = k0; k <= k1; ++k) {
    vec3 cell = unswizzle(vec3(pix, float(k)), gAxis);
    if (triangleOverlapsBox(cell + 0.5f, vec3(0.5f), gA, gB, gC)) {
      visitCell(uvec3(cell));
    }
  }
}
