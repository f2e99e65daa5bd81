// The flux tree of every light-map face (shared/vpl.glsl), one level per
// dispatch: level 0 from the reflective shadow maps (each texel as a VPL,
// shared/light_maps.glsl: rsmTexelVpl — Φ = π · L · A, the mean of its
// channels), level l > 0 the 2×2 sums of level l − 1. z is the face.
#include "shared/constants.glsl"
#include "shared/sampling.glsl"
#include "shared/environment.glsl"
#include "shared/light_maps.glsl"
layout(std430, binding = BINDING_VPL_FLUX) buffer VplFluxTree { float vplFluxTree[]; };
#define VPL_FLUX_TREE
#include "shared/vpl.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
uniform uint uRes;    // the light maps' side
uniform uint uLevel;  // the level written

void main() {
  uint s = fluxTreeSize(uRes, uLevel);
  uvec3 id = gl_GlobalInvocationID;
  if (id.x >= s || id.y >= s) return;
  uint f = id.z;
  float value;
  if (uLevel == 0u) {
    RsmVpl v = rsmTexelVpl(int(f), ivec2(id.xy));
    value = PI * v.area * (v.radiance.x + v.radiance.y + v.radiance.z) / 3.0f;
  } else {
    uint l = uLevel - 1u, cx = 2u * id.x, cy = 2u * id.y;
    value = (fluxTreeNode(uRes, f, l, cx, cy) + fluxTreeNode(uRes, f, l, cx + 1u, cy)) +
            (fluxTreeNode(uRes, f, l, cx, cy + 1u) + fluxTreeNode(uRes, f, l, cx + 1u, cy + 1u));
  }
  vplFluxTree[f * fluxTreeFaceStride(uRes) + fluxTreeOffset(uRes, uLevel) + id.y * s + id.x] = value;
}
