// Virtual point lights (Keller 1997, instant radiosity; VGI §5.3): the VPL
// record the GL many-light modules write and gather, the flux tree their
// first-bounce VPLs are drawn from, and the gathered light — shared with the
// C++ build (illum/methods/vpl.cpp's exact-visibility gather, the tests).
//
// Flux tree: per light-map face, level 0 holds each RSM texel's reflected
// flux (scalar: the mean of Φ_rgb = π · L_rgb · A), level l+1 the sums of
// 2×2 blocks of level l (sizes ⌈res / 2^l⌉, down to 1×1). Drawing a texel
// proportionally to its flux is a descent from the top, splitting u.x
// between the two columns of a node and u.y between the two rows of the
// chosen column, each coordinate rescaled to [0, 1) (hierarchical sample
// warping, Clarberg et al. 2005): a stratified set of u stays stratified over
// the flux.
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
#include "constants.glsl"
#include "lights.glsl"
#include "sampling.glsl"

SHARED_BEGIN

// One VPL: where it is, the side it lights, and the flux Φ it carries.
struct Vpl {
  vec4 position;  // xyz; w = 1 for a VPL, 0 for an empty slot (a chain that ended)
  vec4 normal;    // xyz, towards the side it lights
  vec4 flux;      // rgb Φ (W), w unused
  uvec4 origin;   // x face, y texel x, z texel y of the first-bounce RSM texel; w bounce (0 first)
};

SHARED_FN Vpl vplEmpty() {
  Vpl v;
  v.position = vec4(0.0f);
  v.normal = vec4(0.0f);
  v.flux = vec4(0.0f);
  v.origin = uvec4(0u);
  return v;
}

// Side of level l of a tree over res × res texels.
SHARED_FN uint fluxTreeSize(uint res, uint l) { return (res + (1u << l) - 1u) >> l; }
// Levels of the tree (the last is 1×1).
SHARED_FN uint fluxTreeLevels(uint res) {
  uint l = 0u;
  while (fluxTreeSize(res, l) > 1u) ++l;
  return l + 1u;
}
// Where level l starts within a face's block, and the block's length.
SHARED_FN uint fluxTreeOffset(uint res, uint l) {
  uint o = 0u;
  for (uint j = 0u; j < l; ++j) o += fluxTreeSize(res, j) * fluxTreeSize(res, j);
  return o;
}
SHARED_FN uint fluxTreeFaceStride(uint res) { return fluxTreeOffset(res, fluxTreeLevels(res)); }

// Light tracing from a delta light (the VPLs that `avg` shoots): the flux it
// emits per unit of its intensity (Φ = I · this) and a ray distributed as its
// emission. Point: 4π, uniform directions. Spot with I(θ) = I₀ cos^f θ inside
// cos θ ≥ cos θc: 2π (1 − cos^(f+1) θc) / (f + 1), cos θ drawn by inverting
// that. Directional (irradiance E): the disc of the scene's bounding sphere
// (centre, radius) across its direction, π r², from 2r up-stream. u is
// the stratified pair (the direction, or a directional light's disc point),
// v a second one.
SHARED_FN float lightEmittedFluxScale(SHARED_IN(PackedLight) L, float radius) {
  uint type = uint(L.positionType.w + 0.5f);
  if (type == LIGHT_POINT) return 4.0f * PI;
  if (type == LIGHT_DIRECTIONAL) return PI * radius * radius;
  float e = max(L.intensityFalloff.w, 0.0f) + 1.0f;
  return 2.0f * PI * (1.0f - pow(max(L.directionCosCone.w, 0.0f), e)) / e;
}
// The emitted flux, the mean of its channels (what light tracing splits the rays by).
SHARED_FN float lightEmittedPower(SHARED_IN(PackedLight) L, float radius) {
  return (L.intensityFalloff.x + L.intensityFalloff.y + L.intensityFalloff.z) / 3.0f *
         lightEmittedFluxScale(L, radius);
}
struct LightRay {
  vec3 origin, dir;
};
SHARED_FN LightRay sampleLightRay(SHARED_IN(PackedLight) L, vec2 u, vec2 v, vec3 centre, float radius) {
  uint type = uint(L.positionType.w + 0.5f);
  vec3 axis = vec3(L.directionCosCone.x, L.directionCosCone.y, L.directionCosCone.z);
  LightRay r;
  r.origin = vec3(L.positionType.x, L.positionType.y, L.positionType.z);
  if (type == LIGHT_POINT) {
    float z = 1.0f - 2.0f * u.x, s = sqrt(max(0.0f, 1.0f - z * z)), phi = 2.0f * PI * u.y;
    r.dir = vec3(s * cos(phi), s * sin(phi), z);
    return r;
  }
  Basis b = makeBasis(axis);
  if (type == LIGHT_DIRECTIONAL) {
    // The direction is fixed: the stratified u places the ray on the disc (v is not needed).
    float rr = radius * sqrt(u.x), phi = 2.0f * PI * u.y;
    r.origin = centre - axis * (2.0f * radius) + b.t * (rr * cos(phi)) + b.b * (rr * sin(phi));
    r.dir = axis;
    return r;
  }
  float e = max(L.intensityFalloff.w, 0.0f) + 1.0f;
  float lo = pow(max(L.directionCosCone.w, 0.0f), e);
  float cosT = pow(max(1.0f - u.x * (1.0f - lo), 0.0f), 1.0f / e);
  float sinT = sqrt(max(0.0f, 1.0f - cosT * cosT)), phi = 2.0f * PI * u.y;
  r.dir = basisToWorld(b, vec3(sinT * cos(phi), sinT * sin(phi), cosT));
  return r;
}

// The interleave subset (of k²) of gather pixel q: chains i with i mod k² equal to it.
SHARED_FN uint vplSubset(ivec2 q, int k) { return uint(q.x % k + k * (q.y % k)); }

// What one VPL adds to the gather at receiver p (normal n), visibility
// aside: Φ · cos θ_v · cos θ_x / (π² · max(d², dMin²)) — times the receiver's
// diffuse albedo, the radiance it reflects (albedo/π · E, E = Φ/π · cos θ_v ·
// cos θ_x / d²). dMin is the clamp of the 1/d² singularity (0: none).
// Returns 0 for an empty slot, or a receiver behind the VPL or facing away.
SHARED_FN vec3 vplGather(SHARED_IN(Vpl) v, vec3 p, vec3 n, float dMin2) {
  if (v.position.w == 0.0f) return vec3(0.0f);
  vec3 d = vec3(v.position.x, v.position.y, v.position.z) - p;
  float d2 = dot(d, d);
  if (!(d2 > 0.0f)) return vec3(0.0f);
  vec3 w = d / sqrt(d2);
  float cosX = dot(n, w);
  float cosV = -dot(vec3(v.normal.x, v.normal.y, v.normal.z), w);
  if (cosX <= 0.0f || cosV <= 0.0f) return vec3(0.0f);
  return vec3(v.flux.x, v.flux.y, v.flux.z) * (cosX * cosV * (INV_PI * INV_PI) / max(d2, dMin2));
}

// The VPL shadow-map test's depth slack at a receiver (gather.comp's
// shadowMapSees): `biasTexels` of the map's angular texel `texel` at the
// receiver's distance `dist`, plus the drawn occluders' `tolerance` (a
// simplified surface may lie that far in front of the receiver's own), both
// over `cosine`, the receiver's towards the VPL, at least 0.2 (a plane seen
// at a grazing angle spans more depth per texel and per offset).
SHARED_FN float vplShadowSlack(float biasTexels, float texel, float dist, float tolerance, float cosine) {
  return (biasTexels * texel * dist + tolerance) / max(cosine, 0.2f);
}

SHARED_END

// The descent itself reads the tree where it lives: an SSBO named vplFluxTree
// in GLSL (a shader that reads it declares it and defines VPL_FLUX_TREE
// before this include), an array in C++.
#if defined(__cplusplus) || defined(VPL_FLUX_TREE)
#ifdef __cplusplus
#define VPL_FLUX_TREE_PARAM , const float* vplFluxTree
#define VPL_FLUX_TREE_ARG , vplFluxTree
#else
#define VPL_FLUX_TREE_PARAM
#define VPL_FLUX_TREE_ARG
#endif

SHARED_BEGIN

// Splits u between two weights a and b: fluxSplitP is a's share, u < it takes
// a; fluxSplitU rescales u to [0, 1) within the side taken.
SHARED_FN float fluxSplitP(float a, float b) { return a + b > 0.0f ? a / (a + b) : 0.5f; }
SHARED_FN float fluxSplitU(float p, float u) {
  float r = u >= p ? (u - p) / max(1.0f - p, 1e-30f) : u / max(p, 1e-30f);
  return min(r, 0.99999994f);
}

// The tree value of node (x, y) of level l of face f, 0 outside the level.
SHARED_FN float fluxTreeNode(uint res, uint f, uint l, uint x, uint y VPL_FLUX_TREE_PARAM) {
  uint s = fluxTreeSize(res, l);
  if (x >= s || y >= s) return 0.0f;
  return vplFluxTree[f * fluxTreeFaceStride(res) + fluxTreeOffset(res, l) + y * s + x];
}

// The texel of face f drawn by u (the face's top value > 0), by the descent above.
SHARED_FN uvec2 fluxTreeDescend(uint res, uint f, vec2 u VPL_FLUX_TREE_PARAM) {
  uint x = 0u, y = 0u;
  for (uint l = fluxTreeLevels(res) - 1u; l > 0u; --l) {
    uint cx = 2u * x, cy = 2u * y;
    float a = fluxTreeNode(res, f, l - 1u, cx, cy VPL_FLUX_TREE_ARG) +
              fluxTreeNode(res, f, l - 1u, cx, cy + 1u VPL_FLUX_TREE_ARG);
    float b = fluxTreeNode(res, f, l - 1u, cx + 1u, cy VPL_FLUX_TREE_ARG) +
              fluxTreeNode(res, f, l - 1u, cx + 1u, cy + 1u VPL_FLUX_TREE_ARG);
    float px = fluxSplitP(a, b);
    x = u.x >= px ? cx + 1u : cx;
    u.x = fluxSplitU(px, u.x);
    float c0 = fluxTreeNode(res, f, l - 1u, x, cy VPL_FLUX_TREE_ARG);
    float c1 = fluxTreeNode(res, f, l - 1u, x, cy + 1u VPL_FLUX_TREE_ARG);
    float py = fluxSplitP(c0, c1);
    y = u.y >= py ? cy + 1u : cy;
    u.y = fluxSplitU(py, u.y);
  }
  return uvec2(x, y);
}

SHARED_END
#endif
