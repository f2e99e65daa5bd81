// One (triangle, cell) pair of vct's radiance injection, for both of its paths: the
// fragment path (inject.frag.glsl, per cell of a conservative fragment's column) and,
// INJECT_HYBRID, the triangle-parallel path of small triangles in the geometry shader
// (voxelize/conservative.geom.glsl). The cell takes the direct diffuse radiance leaving
// the triangle's point closest to the cell centre — both faces, through every light's
// shadow map (lightMapsDirect, the deferred direct pass's own function) — into the
// fixed-point sums (inject_sums.glsl); INJECT_DIRECTIONAL: also the direction it leaves in.
#include "shared/constants.glsl"
#include "shared/sampling.glsl"
#include "shared/brdf.glsl"
#include "shared/environment.glsl"
#include "shared/gpu_scene.glsl"
#include "shared/light_maps.glsl"
#include "shared/closest_point.glsl"
#include "inject_sums.glsl"
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

// The triangle's grid corners (a, b, c), world corners and uvs, its unit world normal (0: degenerate)
// and index (the material's); cell c.
void injectPair(uvec3 c, vec3 a, vec3 b, vec3 cc, vec3 w0, vec3 w1, vec3 w2, vec2 uv0, vec2 uv1, vec2 uv2,
                vec3 worldNormal, int triangle) {
  uint slot = injectSlot(c);
  if (slot == INJECT_NO_SLOT) return;  // a cell outside the octree: not lit at all
  vec3 q = closestPointOnTriangle(vec3(c) + 0.5f, a, b, cc);
  vec2 w = barycentric(q, a, b, cc);
  vec3 p = w0 + w.x * (w1 - w0) + w.y * (w2 - w0);
  vec2 uv = uv0 + w.x * (uv1 - uv0) + w.y * (uv2 - uv0);
  int m = triMaterial[triangle];
  vec3 albedo = materials[m].albedoLayer.xyz;
  float layer = materials[m].albedoLayer.w;
  if (layer >= 0.0f) albedo *= textureLod(albedoTextures, vec3(uv.x, 1.0f - uv.y, layer), 0.0f).xyz;
  BrdfParams diffuse;
  diffuse.albedo = albedo;
  diffuse.ks = vec3(0.0f);
  diffuse.exponent = 1.0f;
  vec3 n = worldNormal;
  vec3 Lfront = vec3(0.0f), Lback = vec3(0.0f);
  if (dot(n, n) > 0.0f) {
    TwoSided L = lightMapsDirectTwoSided(diffuse, p, n, uShadowBias, uNormalOffset);
    Lfront = L.front;
    Lback = L.back;
  }
  injectAdd(slot, Lfront + Lback);
#if defined(INJECT_DIRECTIONAL) && !defined(INJECT_MAX)
  injectDirection(slot, n, Lfront, Lback);
#endif
}
