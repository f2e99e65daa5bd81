// Voxel cone tracing (Crassin et al., "Interactive Indirect Illumination Using
// Voxel Cone Tracing", 2011; Dinse 2015 §3.2–3.3; Basgier 2015 §5.2) through
// the pre-integrated volume of voxelize/value_textures: the radiance channel
// premultiplied (L·α, α = opacity), with its isotropic chain and, under
// VCT_ANISOTROPIC, the six-direction chain from the grid's level 1.
//
// A cone (apex, unit axis d, half-angle tan θ) is marched front to back:
// at distance t its diameter is D = max(2 t tan θ, v) (v a voxel), the sample
// is taken at mip level log2(D / v) (quadrilinear: trilinear within a level,
// linear between levels), the step is uConeStep · D (the last one ends at the
// cone's length), and the sample's opacity is corrected for the step,
// α' = 1 − (1 − α)^(step / cell) with cell = v · 2^lod, so a medium gives the
// same transmittance whatever the step (Crassin et al. §4.2; the VCT thesis'
// Algorithm 1 omits it). Premultiplied radiance scales with α'/α:
//   C += (1 − A) · c · α'/α,   A += (1 − A) · α'.
// Anisotropic lookups mix the three faces seen along d by |d| (the VCT
// thesis, Alg. 1; VCT_ABS_WEIGHTS) — the weights sum to up to √3, which keeps
// a thin wall hit obliquely opaque — or by d² (anisoWeights, summing to 1:
// such a wall reads cos²θ + sin²θ·2^-l, and the closed sphere's bounce drops
// from 0.92 to 0.75 of the exact); below level 1 the level-0 cell
// (isotropic) is blended in.
// Receiver guard (ours; `plane_guard`): a cone from a surface samples at
// height h = h0 + t·cos(d, n) above the receiver's tangent plane; a level-l
// sample blends texels reaching 1.5·2^l voxels below it and the receiver's
// voxels reach a voxel above its plane, so the level is capped at the integer
// floor(log2((h − v) / 1.5 v)) (an integer: trilinear filtering between
// levels would read the coarser one) and the step shrinks to that footprint;
// the receiver's own voxels never enter its cones (without it an open floor
// occludes itself: AO 0.56 instead of 1 with the anisotropic chain).
// guardSlope < 0: no cap (tests).
// Level cap (`max_level`, VCT_MAX_LEVEL): no sample above that level, the
// step shrinking to the footprint sampled (a capped level with the cone's own
// step would step over walls); a coarse texel averages both sides of a wall.
// Directional level 0 (ours; VCT_DIRECTIONAL, the dense volume): a level-0
// sample's radiance is seen from the cone's side, times directionalFacing(−d,
// D) (shared/value_grid.glsl), D the cells' direction of leaving light; the
// anisotropic chain's first level was built through the same weights.
// Empty-space skipping (Dinse 2015 Alg. 1): where a sample is empty, the
// largest empty parent texel of the isotropic chain around the sample is left
// in one jump — samples that would have blended in a non-empty neighbour
// inside that texel are skipped (the artefact the thesis shows, Fig. 18a).
//
// Bound by the volume's bindCones (illum/resources/cone_volume.h: the dense
// ConeVolume, or the sparse octree's, CONE_SVO): the textures, the grid
// uniforms, uVoxelSize, uMaxLod, uConeStep. Both volumes answer the same two
// questions — coneSample (the volume at a grid point, level and direction) and
// emptySkip — so the cones are the same code whatever the storage. A pass that
// defines CONE_SAMPLE supplies its own coneSample() (the tests' uniform medium).
#include "shared/constants.glsl"
#include "shared/sampling.glsl"
#include "shared/value_textures.glsl"
#include "voxelize/grid_uniforms.glsl"
#ifdef CONE_SVO
#include "shared/sparse_octree_lookup.glsl"
#endif
uniform float uVoxelSize;  // world size of a level-0 cell
uniform float uMaxLod;     // the chains' last level
uniform float uConeStep;   // step = uConeStep × the cone's diameter
#ifdef VCT_DIRECTIONAL
// The level-0 direction of each cell's leaving light (`directional`; 0 where empty).
layout(binding = TEXUNIT_VALUE_DIRECTION) uniform sampler3D coneDirection;
#endif

#ifdef VCT_ABS_WEIGHTS
vec3 coneFaceWeights(vec3 d) { return abs(d); }  // the thesis' weights: Σ up to √3, so an oblique wall stays opaque
#else
vec3 coneFaceWeights(vec3 d) { return anisoWeights(d); }
#endif

// World distance from grid point q along dg out of its texel at mip level `level`.
float emptyBoxExit(vec3 q, vec3 dg, int level) {
  float side = exp2(float(level));
  vec3 lo = floor(q / side) * side, hi = lo + side;
  float t = 1e30f;
  for (int a = 0; a < 3; ++a) {
    if (dg[a] > 1e-12f) t = min(t, (hi[a] - q[a]) / dg[a]);
    if (dg[a] < -1e-12f) t = min(t, (lo[a] - q[a]) / dg[a]);
  }
  return t;
}

#if !defined(CONE_SAMPLE) && !defined(CONE_SVO)
// The volume along unit direction d at grid point q (cells), mip level lod
// (premultiplied rgb, opacity w).
vec4 coneSample(vec3 q, vec3 d, float lod) {
  vec3 uvw = q / vec3(uResolution.xyz);
#ifdef VCT_ANISOTROPIC
  // Level 0 itself (a fractional lod would blend the isotropic level 1 in too).
  vec4 s0 = textureLod(valueRadiance, uvw, 0.0f);
#ifdef VCT_DIRECTIONAL
  // Seen from the cone's side: the blended D over the occupancy it blends.
  if (s0.w > 0.0f) s0.xyz *= directionalFacing(-d, textureLod(coneDirection, uvw, 0.0f).xyz / s0.w);
#endif
  vec3 w = coneFaceWeights(d);
  if (lod <= 0.0f || uMaxLod < 1.0f) return s0;
  if (lod < 1.0f) return mix(s0, valueAniso(uvw, d, 1.0f, w), lod);
  return valueAniso(uvw, d, lod, w);
#else
  return textureLod(valueRadiance, uvw, lod);
#endif
}

// World distance from grid point q along dg (grid cells per world unit) out of
// the largest empty texel around q of the isotropic chain, from level
// floor(lod) up; 0 where the texel at floor(lod) is not empty.
float emptySkip(vec3 q, vec3 dg, float lod) {
  int level = -1;
  ivec3 cell = ivec3(floor(q));
  for (int l = int(floor(lod)); l <= int(uMaxLod); ++l) {
    if (texelFetch(valueRadiance, cell >> l, l).w > 0.0f) break;
    level = l;
  }
  if (level < 0) return 0.0f;
  return emptyBoxExit(q, dg, level);
}
#endif


#if !defined(CONE_SAMPLE) && defined(CONE_SVO)
// The same through the octree: level l of the dense chain is the octree's
// level D − l; a fractional level blends two (quadrilinear), each one stencil
// lookup and one hardware trilinear fetch per pool.
vec4 svoIso(vec3 q, float level) {
  SvoStencil s = svoStencil(q, uSvoDepth - uint(level));
  if (!s.found) return vec4(0.0f);
  return s.scale * textureLod(valueRadiance, svoPoolUvw(s.tile - uSvoIsoBase, uSvoIsoBricks, s.u), 0.0f);
}
vec4 svoFace(uint f, vec3 uvw) {
  switch (f) {
    case 0u: return textureLod(valueAniso0, uvw, 0.0f);
    case 1u: return textureLod(valueAniso1, uvw, 0.0f);
    case 2u: return textureLod(valueAniso2, uvw, 0.0f);
    case 3u: return textureLod(valueAniso3, uvw, 0.0f);
    case 4u: return textureLod(valueAniso4, uvw, 0.0f);
    default: return textureLod(valueAniso5, uvw, 0.0f);
  }
}
vec4 svoAniso(vec3 q, vec3 d, float level, vec3 w) {
  SvoStencil s = svoStencil(q, uSvoDepth - uint(level));
  if (!s.found) return vec4(0.0f);
  vec3 uvw = svoPoolUvw(s.tile, uSvoFaceBricks, s.u);
  uvec3 f = anisoFaces(d);
  return s.scale * (w.x * svoFace(f.x, uvw) + w.y * svoFace(f.y, uvw) + w.z * svoFace(f.z, uvw));
}
vec4 coneSample(vec3 q, vec3 d, float lod) {
  float l0 = floor(lod), t = lod - l0;
#ifdef VCT_ANISOTROPIC
  vec3 w = coneFaceWeights(d);
  if (lod <= 0.0f || uMaxLod < 1.0f) return svoIso(q, 0.0f);
  if (lod < 1.0f) return mix(svoIso(q, 0.0f), svoAniso(q, d, 1.0f, w), lod);
  vec4 a = svoAniso(q, d, l0, w);
  return t > 0.0f ? mix(a, svoAniso(q, d, l0 + 1.0f, w), t) : a;
#else
  vec4 a = svoIso(q, l0);
  return t > 0.0f ? mix(a, svoIso(q, l0 + 1.0f), t) : a;
#endif
}

// emptySkip through the octree: the coarsest node without fragments on the way
// down to q's leaf (SVO_OCCUPIED clear: an empty tile sibling, a dilated node,
// an empty leaf) is the dense chain's largest empty texel.
float emptySkip(vec3 q, vec3 dg, float lod) {
  uvec3 cell = uvec3(min(ivec3(floor(q)), ivec3((1 << int(uSvoDepth)) - 1)));
  uint n = 0u;
  int level = -1;
  for (uint l = 0u; l <= uSvoDepth; ++l) {
    uint v = svoNodes[n];
    if (!svoOccupied(v)) {
      level = int(uSvoDepth - l);
      break;
    }
    if (l < uSvoDepth) n = svoChild(v) + svoOctant(cell, uSvoDepth - 1u - l);
  }
  if (level < int(floor(lod))) return 0.0f;
  return emptyBoxExit(q, dg, level);
}
#endif

struct ConeResult {
  vec3 radiance;    // gathered front to back (premultiplied)
  float opacity;    // A
  float occlusion;  // within aoRadius, each sample's α' weakened by 1/(1 + λ t / aoRadius)
  float escaped;    // 1 if the cone left the grid (the environment shows through 1 − A)
  int samples;
};

const int kMaxConeSamples = 4096;

// The cone from `apex` along unit d with half-angle tan θ = tanHalf, up to maxDist.
ConeResult traceCone(vec3 apex, vec3 d, float tanHalf, float maxDist, float aoRadius, float falloff, bool skipEmpty,
                     float guardHeight, float guardSlope) {
  GridParams g = gridFromUniforms();
  vec3 res = vec3(g.resolution.xyz);
  vec3 qa = worldToGrid(g, apex);
  vec3 dg = worldToGrid(g, apex + d) - qa;
  ConeResult r;
  r.radiance = vec3(0.0f);
  r.opacity = 0.0f;
  r.occlusion = 0.0f;
  r.escaped = 0.0f;
  r.samples = 0;
  float t = 0.0f;
  for (int i = 0; i < kMaxConeSamples && t < maxDist && r.opacity < 0.999f; ++i) {
    float diameter = max(2.0f * t * tanHalf, uVoxelSize);
    float lod = min(log2(diameter / uVoxelSize), uMaxLod);
    float step = min(uConeStep * diameter, maxDist - t);
#ifdef VCT_MAX_LEVEL
    if (lod > float(VCT_MAX_LEVEL)) {  // `max_level`: and the step follows the footprint sampled
      lod = float(VCT_MAX_LEVEL);
      step = min(uConeStep * uVoxelSize * exp2(lod), maxDist - t);
    }
#endif
    if (guardSlope >= 0.0f) {
      float h = guardHeight + (t + 0.5f * step) * guardSlope;
      float cap = max(floor(log2(max(h - uVoxelSize, 1e-30f) / (1.5f * uVoxelSize))), 0.0f);
      if (lod > cap) {
        lod = cap;  // and the step follows the footprint actually sampled
        step = min(uConeStep * uVoxelSize * exp2(lod), maxDist - t);
      }
    }
    vec3 q = qa + dg * (t + 0.5f * step);
    if (any(lessThan(q, vec3(0.0f))) || any(greaterThan(q, res))) {
      r.escaped = 1.0f;
      break;
    }
    vec4 s = coneSample(q, d, lod);
    ++r.samples;
    float a = clamp(s.w, 0.0f, 1.0f);
    float cell = uVoxelSize * exp2(lod);
    float ac = 1.0f - pow(1.0f - a, step / cell);
    // Premultiplied: the colour scales with α'/α (α unclamped: |d| weights may sum past 1).
    if (s.w > 1e-7f) r.radiance += (1.0f - r.opacity) * vec3(s.x, s.y, s.z) * (ac / s.w);
    if (t < aoRadius) {
      float aa = 1.0f - pow(1.0f - a, min(step, aoRadius - t) / cell);
      r.occlusion += (1.0f - r.occlusion) * aa / (1.0f + falloff * t / aoRadius);
    }
    r.opacity += (1.0f - r.opacity) * ac;
    float advance = step;
#ifndef CONE_SAMPLE
    if (skipEmpty && a < 1e-4f) advance = max(step, emptySkip(q, dg, lod) + 0.5f * step);
#endif
    t += advance;
  }
  return r;
}

// A Phong lobe cos^e as a cone: the half-angle where the lobe falls to half
// its peak, cos θ = 2^(−1/e) (e = 1: 60°, 10: 21°, 100: 6.7°, 1000: 2.1°).
float phongConeTanHalf(float e) {
  float c = pow(0.5f, 1.0f / max(e, 1e-3f));
  return sqrt(max(1.0f - c * c, 0.0f)) / max(c, 1e-3f);
}

// The tangent frame of n turned by angle phi about n (the constellations' azimuth).
Basis turnedBasis(vec3 n, float phi) {
  Basis b = makeBasis(n);
  vec3 t = cos(phi) * b.t + sin(phi) * b.b;
  b.b = cross(n, t);
  b.t = t;
  return b;
}
