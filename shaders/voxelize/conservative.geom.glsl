// Three-axis conservative voxelization, triangle setup (Basgier 2015 §3.2–3.3,
// after Crassin & Green 2012 and Hasselgren et al. 2005): project each triangle
// along its dominant axis (largest projected area, so at most ~3 cells deep per
// pixel) and push its edges out by a pixel's semi-diagonal so every pixel it
// touches gets a fragment.
// HYBRID (Rauwendaal & Bailey 2013, as Basgier 2015 §3.4–3.5 builds it in one
// pass): a triangle whose area projected on its dominant plane is under
// uCutoff cells² (and whose box spans at most kHybridMaxCells cells) is
// voxelized here, triangle-parallel — every cell of its bounding box that the
// triangle–box test confirms is set — and emits nothing; larger ones go on to
// the fragment-parallel path. uHybridCounts counts both kinds.
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
in vec3 vGrid[];
uniform uvec4 uResolution;
uniform float uViewport;  // the square viewport's side, ≥ every grid side
flat out int gAxis;       // dominant axis: 0 = x, 1 = y, 2 = z
flat out vec3 gA;
flat out vec3 gB;
flat out vec3 gC;
#ifdef CONSERVATIVE_VALUES
in vec3 vWorld[];
in vec2 vUv[];
flat out vec3 gWorldNormal;  // the triangle's unit normal in world space
flat out vec2 gUvCentroid;
flat out vec3 gWorld0;  // the corners in world space (gA, gB, gC's), and their uvs
flat out vec3 gWorld1;
flat out vec3 gWorld2;
flat out vec2 gUv0;
flat out vec2 gUv1;
flat out vec2 gUv2;
#endif

// (Included for both small-triangle paths below, outside their #ifdefs: an include is expanded once.)
#include "shared/voxel_grid.glsl"
#include "shared/triangle_box.glsl"
#include "shared/bindings.glsl"
#ifdef HYBRID
layout(std430, binding = BINDING_GRID_WORDS) buffer Columns { uint words[]; };
layout(std430, binding = BINDING_VOXEL_COUNTER) buffer HybridCounts { uint hybridCounts[2]; };  // small, large
uniform float uCutoff;
const int kHybridMaxCells = 512;
// A cell the small triangle overlaps: its bit set.
void smallTriangleCell(ivec3 c, vec3 a, vec3 b, vec3 cc) {
  atomicOr(words[columnWordIndex(uint(c.x), uint(c.y), depthWord(uint(c.z)), uResolution)], depthBit(uint(c.z)));
}
#endif

#ifdef INJECT_HYBRID
// vct's injection, triangle-parallel for small triangles (as HYBRID does for the
// binary grid): a triangle whose bounding box spans at most uInjectSmallCells
// cells lights every cell of it the triangle–box test confirms (the pairs the
// fragment path would visit) here and emits nothing; larger ones go on
// (uInjectSmallCells: `inject_small`; 0: none is small).
#include "illum/vct/inject_pair.glsl"
uniform int uInjectSmallCells;
vec3 smallNormal;  // the triangle's unit world normal (0: degenerate), set before its cells
// A cell the small triangle overlaps: the pair lit.
void smallTriangleCell(ivec3 c, vec3 a, vec3 b, vec3 cc) {
  injectPair(uvec3(c), a, b, cc, vWorld[0], vWorld[1], vWorld[2], vUv[0], vUv[1], vUv[2], smallNormal,
             gl_PrimitiveIDIn);
}
#endif

#if defined(HYBRID) || defined(INJECT_HYBRID)
// The triangle-parallel path of both: calls smallTriangleCell for every cell of the triangle's
// bounding box (grid coordinates) that the triangle–box test confirms; false (nothing visited) when
// the box spans more than maxCells cells.
bool visitSmallTriangle(vec3 a, vec3 b, vec3 c, int maxCells) {
  ivec3 res = ivec3(uResolution.xyz);
  ivec3 lo = clamp(ivec3(floor(min(a, min(b, c)))), ivec3(0), res - 1);
  ivec3 hi = clamp(ivec3(floor(max(a, max(b, c)))), ivec3(0), res - 1);
  ivec3 span = hi - lo + 1;
  if (span.x * span.y * span.z > maxCells) return false;
  for (int z = lo.z; z <= hi.z; ++z)
    for (int y = lo.y; y <= hi.y; ++y)
      for (int x = lo.x; x <= hi.x; ++x)
        if (triangleOverlapsBox(vec3(x, y, z) + 0.5f, vec3(0.5f), a, b, c)) smallTriangleCell(ivec3(x, y, z), a, b, c);
  return true;
}
#endif

// Grid coordinates → (u, v, w) with w along `axis`.
vec3 swizzle(vec3 p, int axis) {
  if (axis == 0) return vec3(p.y, p.z, p.x);
  if (axis == 1) return vec3(p.z, p.x, p.y);
  return p;
}

void main() {
  vec3 n = cross(vGrid[1] - vGrid[0], vGrid[2] - vGrid[0]);
  vec3 an = abs(n);
  int axis = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
#ifdef HYBRID
  // The area projected on the dominant plane: half the normal's dominant component.
  if (0.5f * max(an.x, max(an.y, an.z)) < uCutoff && visitSmallTriangle(vGrid[0], vGrid[1], vGrid[2], kHybridMaxCells)) {
    atomicAdd(hybridCounts[0], 1u);
    return;
  }
  atomicAdd(hybridCounts[1], 1u);
#endif
#ifdef INJECT_HYBRID
#ifdef INJECT_REGION
  // A moving frame's injection: a triangle whose box (a cell of margin) misses the region has no
  // pair there — nothing to rasterize.
  vec3 tlo = min(vGrid[0], min(vGrid[1], vGrid[2])) - 1.0f, thi = max(vGrid[0], max(vGrid[1], vGrid[2])) + 1.0f;
  if (any(lessThan(thi, vec3(uRegionLo))) || any(greaterThan(tlo, vec3(uRegionHi)))) return;
#endif
  vec3 wn = cross(vWorld[1] - vWorld[0], vWorld[2] - vWorld[0]);
  smallNormal = dot(wn, wn) > 0.0f ? normalize(wn) : vec3(0.0f);
  if (visitSmallTriangle(vGrid[0], vGrid[1], vGrid[2], uInjectSmallCells)) return;
#endif
  vec2 p0 = swizzle(vGrid[0], axis).xy, p1 = swizzle(vGrid[1], axis).xy, p2 = swizzle(vGrid[2], axis).xy;
  if ((p1.x - p0.x) * (p2.y - p0.y) - (p1.y - p0.y) * (p2.x - p0.x) < 0.0f) {  // make it counter-clockwise
    vec2 t = p1;
    p1 = p2;
    p2 = t;
  }
  // Edge lines (interior positive), each moved out by the semi-diagonal.
  vec3 e0 = cross(vec3(p0, 1.0f), vec3(p1, 1.0f));
  vec3 e1 = cross(vec3(p1, 1.0f), vec3(p2, 1.0f));
  vec3 e2 = cross(vec3(p2, 1.0f), vec3(p0, 1.0f));
  e0.z += 0.5f * (abs(e0.x) + abs(e0.y));
  e1.z += 0.5f * (abs(e1.x) + abs(e1.y));
  e2.z += 0.5f * (abs(e2.x) + abs(e2.y));
  vec3 q[3];
  q[0] = cross(e2, e0);
  q[1] = cross(e0, e1);
  q[2] = cross(e1, e2);
  for (int i = 0; i < 3; ++i) {
    vec2 s = q[i].xy / q[i].z;  // grid cells along (u, v) = pixels
    gAxis = axis;
    gA = vGrid[0];
    gB = vGrid[1];
    gC = vGrid[2];
#ifdef CONSERVATIVE_VALUES
    vec3 wn = cross(vWorld[1] - vWorld[0], vWorld[2] - vWorld[0]);
    gWorldNormal = dot(wn, wn) > 0.0f ? normalize(wn) : vec3(0.0f);
    gUvCentroid = (vUv[0] + vUv[1] + vUv[2]) / 3.0f;
    gWorld0 = vWorld[0];
    gWorld1 = vWorld[1];
    gWorld2 = vWorld[2];
    gUv0 = vUv[0];
    gUv1 = vUv[1];
    gUv2 = vUv[2];
    gl_PrimitiveID = gl_PrimitiveIDIn;
#endif
    gl_Position = vec4(s / uViewport * 2.0f - 1.0f, 0.0f, 1.0f);
    EmitVertex();
  }
  EndPrimitive();
}
