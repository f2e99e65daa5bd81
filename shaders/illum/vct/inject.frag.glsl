// Voxel cone tracing's radiance injection (Dinse 2015 §3.1: the scene is
// voxelized with conservative rasterization and every fragment is lit with a
// diffuse direct-lighting model through the shadow map), per fragment of the
// three-axis conservative rasterization (voxelize/conservative.geom +
// conservative_cells.glsl): each cell the triangle overlaps (triangle–box
// test) takes the direct diffuse radiance leaving the triangle's point
// closest to the cell centre — both faces, through every light's shadow map
// (lightMapsDirect, the deferred direct pass's own function) — into the
// multi-valued grid's fixed-point radiance sums and counts
// (shared/value_grid.glsl), so voxelize/value_textures resolves and
// pre-integrates them like the atlas voxelizer's radiance channel.
// INJECT_DIRECTIONAL: also the direction it leaves in (each side's light
// along its side's normal; inject_sums.glsl: injectDirection).
// INJECT_MAX: the first pass, only the largest radiance (float bits, atomicMax:
// the fixed-point range of the second). INJECT_SVO: the sums are the sparse
// octree's leaves' (voxelize/sparse_octree.h; a cell's slot found by
// descending the tree; a cell not in the tree is left out, as the dense
// resolve leaves out a cell the binary grid does not hold).
#include "shared/constants.glsl"
#include "shared/sampling.glsl"
#include "shared/brdf.glsl"
#include "shared/environment.glsl"
#include "shared/gpu_scene.glsl"
#include "shared/light_maps.glsl"
#include "shared/closest_point.glsl"
#include "voxelize/conservative_cells.glsl"
#include "inject_sums.glsl"
flat in vec3 gWorldNormal;
flat in vec3 gWorld0;
flat in vec3 gWorld1;
flat in vec3 gWorld2;
flat in vec2 gUv0;
flat in vec2 gUv1;
flat in vec2 gUv2;
uniform float uShadowBias;    // in shadow-map texels
uniform float uNormalOffset;  // in shadow-map texels

// Barycentric weights (of b, c) of q on triangle (a, b, c).
vec2 barycentric(vec3 q, vec3 a, vec3 b, vec3 c) {
  vec3 v0 = b - a, v1 = c - a, v2 = q - a;
  float d00 = dot(v0, v0), d01 = dot(v0, v1), d11 = dot(v1, v1), d20 = dot(v2, v0), d21 = dot(v2, v1);
  float den = d00 * d11 - d01 * d01;
  if (den <= 0.0f) return vec2(0.0f);
  return vec2(d11 * d20 - d01 * d21, d00 * d21 - d01 * d20) / den;
}

void visitCell(uvec3 c) {
  uint slot = injectSlot(c);
  if (slot == INJECT_NO_SLOT) return;  // a cell outside the octree: not lit at all
  vec3 q = closestPointOnTriangle(vec3(c) + 0.5f, gA, gB, gC);
  vec2 w = barycentric(q, gA, gB, gC);
  vec3 p = gWorld0 + w.x * (gWorld1 - gWorld0) + w.y * (gWorld2 - gWorld0);
  vec2 uv = gUv0 + w.x * (gUv1 - gUv0) + w.y * (gUv2 - gUv0);
  int m = triMaterial[gl_PrimitiveID];
  vec3 albedo = materials[m].albedoLayer.xyz;
  float layer = materials[m].albedoLayer.w;
  if (layer >= 0.0f) albedo *= texture(albedoTextures, vec3(uv.x, 1.0f - uv.y, layer)).xyz;
  BrdfParams diffuse;
  diffuse.albedo = albedo;
  diffuse.ks = vec3(0.0f);
  diffuse.exponent = 1.0f;
  vec3 n = gWorldNormal;
  vec3 Lfront = vec3(0.0f), Lback = vec3(0.0f);
  if (dot(n, n) > 0.0f) {
    Lfront = lightMapsDirect(diffuse, p, n, n, n, uShadowBias, uNormalOffset);
    Lback = lightMapsDirect(diffuse, p, -n, -n, -n, uShadowBias, uNormalOffset);
  }
  injectAdd(slot, Lfront + Lback);
#if defined(INJECT_DIRECTIONAL) && !defined(INJECT_MAX)
  injectDirection(slot, n, Lfront, Lback);
#endif
}

void main() { visitTriangleCells(); }
