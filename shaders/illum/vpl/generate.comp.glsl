// VPL generation (VGI §5.3), one invocation per chain i < uChains:
//   bounce 0: an RSM texel drawn proportionally to its reflected flux
//     (Dachsbacher and Stamminger 2005, importance-sampled by flux): face by
//     the faces' totals, texel by the descent of the flux tree
//     (shared/vpl.glsl), with u the chain's point of the R2 sequence rotated
//     per sample — so the chains stratify the flux and every sample draws a
//     new set. The VPL sits at the texel's surface point with its normal and
//     carries Φ_texel / (N · p_texel) = total / N · Φ_rgb / Φ: equal-power VPLs.
//   bounce b ≥ 1: from the previous VPL a cosine-distributed ray (the VPLs
//     reflect diffusely) through the voxel grid (traverse/tracer.glsl, the
//     chosen tracer; illum/voxel_hits.glsl: trace with the own-band pass rule,
//     hitVertex from the multi-valued grids), a VPL at the hit with the cell's
//     mean normal and Φ · albedo (f·cos/pdf = albedo for cosine sampling).
// A chain that ends (nothing lit, the ray leaves the grid, a cell without
// values) leaves empty slots (position.w = 0) for its remaining bounces.
#include "shared/constants.glsl"
#include "shared/sampling.glsl"
#include "shared/brdf.glsl"
#include "shared/environment.glsl"
#include "shared/gpu_scene.glsl"
#include "shared/light_maps.glsl"
#include "shared/value_textures.glsl"
layout(std430, binding = BINDING_VPL_FLUX) readonly buffer VplFluxTree { float vplFluxTree[]; };
#define VPL_FLUX_TREE
#include "shared/vpl.glsl"
#include "traverse/tracer.glsl"
#include "illum/voxel_hits.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = BINDING_VPLS) writeonly buffer Vpls { Vpl vpls[]; };
uniform uint uRes;       // the light maps' side
uniform uint uChains;    // N
uniform int uBounces;    // VPLs per chain
uniform uvec2 uRotation; // this sample's R2 rotation (fixed point)
uniform uint uSeed;
uniform uint uSampleIndex;

float faceTotal(uint f) { return fluxTreeNode(uRes, f, fluxTreeLevels(uRes) - 1u, 0u, 0u); }

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uChains) return;
  int b = 0;
  uint faces = uint(lightFaceCount());
  float total = 0.0f;
  for (uint f = 0u; f < faces; ++f) total += faceTotal(f);
  if (total > 0.0f) {
    vec2 u = r2Point(i, uRotation.x, uRotation.y);
    // The face: u.x split over the faces' totals.
    uint face = 0u;
    float x = u.x * total;
    for (; face + 1u < faces; ++face) {
      float t = faceTotal(face);
      if (x < t) break;
      x -= t;
    }
    float top = faceTotal(face);
    u.x = min(top > 0.0f ? x / top : 0.0f, 0.99999994f);
    uvec2 t = fluxTreeDescend(uRes, face, u);
    float value = fluxTreeNode(uRes, face, 0u, t.x, t.y);
    RsmVpl r = rsmTexelVpl(int(face), ivec2(t));
    if (value > 0.0f && r.valid) {
      Vpl v;
      v.position = vec4(r.position, 1.0f);
      v.normal = vec4(normalize(r.normal), 0.0f);
      v.flux = vec4(PI * r.radiance * r.area * (total / (float(uChains) * value)), 0.0f);
      v.origin = uvec4(face, t.x, t.y, 0u);
      vpls[i] = v;
      b = 1;
      uint rng = rngSeed(i, uSampleIndex, uSeed ^ 0x5bd1e995u);
      for (; b < uBounces; ++b) {
        vec3 n = v.normal.xyz;
        vec2 w = vec2(rngNext(rng), rngNext(rng));
        vec3 d = basisToWorld(makeBasis(n), cosineSampleHemisphere(w));
        vec3 o = v.position.xyz + n * hits.offset;
        float th;
        uvec3 voxel;
        BackProjection bp;
        if (!trace(o, d, n, th, voxel, bp)) break;
        Vertex y;
        if (!hitVertex(o, d, th, voxel, y)) break;
        v.position = vec4(y.p, 1.0f);
        v.normal = vec4(y.n, 0.0f);
        v.flux = vec4(v.flux.xyz * y.brdf.albedo, 0.0f);
        v.origin.w = uint(b);
        vpls[uint(b) * uChains + i] = v;
      }
    }
  }
  for (; b < uBounces; ++b) vpls[uint(b) * uChains + i] = vplEmpty();
}
