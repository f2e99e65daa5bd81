// Per-VPL shadow maps in one atlas (the `avg` module's VPL visibility,
// Bashford-Rogers et al. 2011 §III-C): the projection the raster pass
// (shadow.vert/.frag) writes with and the gather reads back with, so both
// agree texel for texel. Each VPL slot owns a tile of the atlas (vplShadow.kind):
//   - VPL_MAP_HEMICUBE (the default): what a VPL on a surface can see, its
//     hemisphere, in five faces of a cube turned to the VPL's frame (tangent,
//     bitangent, normal: the normal's face and the upper halves of the four
//     side faces; geometry below the VPL's plane clipped away), r×r each, in a
//     3×2 tile whose sixth square stays unused; exact for large triangles;
//   - VPL_MAP_CUBE: six faces along the world axes (the whole sphere), 3×2;
//   - VPL_MAP_PARABOLOID: one paraboloid over the hemisphere, r×r, the paper's
//     choice for scenes of small triangles — a triangle's vertices are
//     projected, its inside is interpolated linearly, so large triangles warp. A map is seen from the VPL lifted vplShadow.lift along its
// normal (an AVG VPL sits up to a cell inside its surface) and stores the
// distance / vplShadow.far to the nearest surface.
#include "shared/bindings.glsl"
#include "shared/sampling.glsl"
#include "shared/vpl.glsl"

#include "params.glsl"
layout(std140, binding = UBO_VPL_SHADOW) uniform VplShadow { VplShadowParams vplShadow; };

int vplShadowFaces() { return vplShadow.kind == VPL_MAP_CUBE ? 6 : (vplShadow.kind == VPL_MAP_HEMICUBE ? 5 : 1); }
bool vplShadowCubeFaces() { return vplShadow.kind != VPL_MAP_PARABOLOID; }
ivec2 vplShadowTileSize() { return vplShadowCubeFaces() ? ivec2(3, 2) * vplShadow.res : ivec2(vplShadow.res); }
// A direction from the map's centre in the frame the faces are laid out in: the VPL's (tangent,
// bitangent, normal) for a hemicube, the world's otherwise.
vec3 vplShadowFrame(Vpl v, vec3 w) {
  if (vplShadow.kind != VPL_MAP_HEMICUBE) return w;
  Basis b = makeBasis(v.normal.xyz);
  return vec3(dot(w, b.t), dot(w, b.b), dot(w, b.n));
}
vec3 vplShadowCentre(Vpl v) { return v.position.xyz + v.normal.xyz * vplShadow.lift; }
// The texel where face f of slot s starts.
ivec2 vplShadowFaceOrigin(uint s, int f) {
  ivec2 tile = ivec2(int(s) % vplShadow.tilesPerRow, int(s) / vplShadow.tilesPerRow) * vplShadowTileSize();
  return tile + ivec2(f % 3, f / 3) * vplShadow.res;
}

// A direction w from the map's centre in face f's clip space: (x, y) over w
// in [−1, 1]² inside the face; w > 0 in front (cube and hemicube: the major
// axis component in the faces' frame, paraboloid: 1 with x, y the paraboloid
// coordinates and z the height over the VPL's tangent plane, ≤ 0 behind).
vec4 vplShadowClip(Vpl v, int f, vec3 w) {
  if (vplShadow.kind == VPL_MAP_PARABOLOID) {
    Basis b = makeBasis(v.normal.xyz);
    vec3 l = vec3(dot(w, b.t), dot(w, b.b), dot(w, b.n)) / max(length(w), 1e-30f);
    return vec4(l.xy / (1.0f + max(l.z, 0.0f)), l.z, 1.0f);
  }
  w = vplShadowFrame(v, w);
  int axis = f / 2;
  float s = f % 2 == 0 ? 1.0f : -1.0f;
  vec3 a = axis == 0 ? w.yzx : (axis == 1 ? w.zxy : w);  // (u, v, major)
  return vec4(a.x * s, a.y, 0.0f, a.z * s);
}
// The face of a cube map that direction w, in the faces' frame (vplShadowFrame), falls in
// (shared/light_maps.glsl's order: +x −x +y −y +z −z; a hemicube has no −z, the face behind the VPL).
int vplShadowFaceOf(vec3 w) {
  vec3 a = abs(w);
  if (a.x >= a.y && a.x >= a.z) return w.x >= 0.0f ? 0 : 1;
  if (a.y >= a.z) return w.y >= 0.0f ? 2 : 3;
  return w.z >= 0.0f ? 4 : 5;
}
