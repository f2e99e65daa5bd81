// Per-VPL shadow maps in one atlas (the `avg` module's VPL visibility,
// Bashford-Rogers et al. 2011 §III-C): the projection the raster pass
// (shadow.vert/.frag) writes with and the gather reads back with, so both
// agree texel for texel. Each VPL slot owns a tile of the atlas: a cube map
// (vplShadow.cube = 1: six faces of r×r, 3×2 in the tile; exact for large
// triangles) or one paraboloid (0: the hemisphere around the VPL's normal,
// r×r, the paper's choice for scenes of small triangles — a triangle's
// vertices are projected, its inside is interpolated linearly, so large
// triangles warp). A map is seen from the VPL lifted vplShadow.lift along its
// normal (an AVG VPL sits up to a cell inside its surface) and stores the
// distance / vplShadow.far to the nearest surface.
#include "shared/bindings.glsl"
#include "shared/sampling.glsl"
#include "shared/vpl.glsl"

#include "params.glsl"
layout(std140, binding = UBO_VPL_SHADOW) uniform VplShadow { VplShadowParams vplShadow; };

int vplShadowFaces() { return vplShadow.cube != 0 ? 6 : 1; }
ivec2 vplShadowTileSize() { return vplShadow.cube != 0 ? ivec2(3, 2) * vplShadow.res : ivec2(vplShadow.res); }
vec3 vplShadowCentre(Vpl v) { return v.position.xyz + v.normal.xyz * vplShadow.lift; }
// The texel where face f of slot s starts.
ivec2 vplShadowFaceOrigin(uint s, int f) {
  ivec2 tile = ivec2(int(s) % vplShadow.tilesPerRow, int(s) / vplShadow.tilesPerRow) * vplShadowTileSize();
  return tile + ivec2(f % 3, f / 3) * vplShadow.res;
}

// A direction w from the map's centre in face f's clip space: (x, y) over w
// in [−1, 1]² inside the face; w > 0 in front (cube: the major axis
// component, paraboloid: 1 with x, y the paraboloid coordinates and z the
// height over the VPL's tangent plane, ≤ 0 behind).
vec4 vplShadowClip(Vpl v, int f, vec3 w) {
  if (vplShadow.cube == 0) {
    Basis b = makeBasis(v.normal.xyz);
    vec3 l = vec3(dot(w, b.t), dot(w, b.b), dot(w, b.n)) / max(length(w), 1e-30f);
    return vec4(l.xy / (1.0f + max(l.z, 0.0f)), l.z, 1.0f);
  }
  int axis = f / 2;
  float s = f % 2 == 0 ? 1.0f : -1.0f;
  vec3 a = axis == 0 ? w.yzx : (axis == 1 ? w.zxy : w);  // (u, v, major)
  return vec4(a.x * s, a.y, 0.0f, a.z * s);
}
// The face of a cube map that direction w falls in (shared/light_maps.glsl's order: +x −x +y −y +z −z).
int vplShadowFaceOf(vec3 w) {
  vec3 a = abs(w);
  if (a.x >= a.y && a.x >= a.z) return w.x >= 0.0f ? 0 : 1;
  if (a.y >= a.z) return w.y >= 0.0f ? 2 : 3;
  return w.z >= 0.0f ? 4 : 5;
}
