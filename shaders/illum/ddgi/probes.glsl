// The DDGI probe field's query (Majercik, Guertin, Nowrouzezahrai, McGuire, "Dynamic Diffuse Global
// Illumination with Ray-Traced Irradiance Fields", JCGT 8(2), 2019, §5 and its code appendix): the
// irradiance over π (the cosine-weighted mean of the arriving radiance, what the probes store) at a
// surface point X with normal n from the 8 probes of its grid cell, each weighted by
// the trilinear weight, a smooth backface term ((1 + cos)/2)² + 0.2 (probes behind the surface count
// little), and the Chebyshev visibility test of its distance moments (the variance shadow map test: a
// probe that sees a nearer surface in X's direction is occluded from X), the test made from X moved
// `bias` along 0.2 n + 0.8 v (the paper's normal and view bias, against self-shadowing); weights under
// 0.2 crushed (w³ / 0.04) so that leaks through thin walls fade. Included by the trace pass (the hits'
// indirect light: the last update's field, so each update adds a bounce) and the shading pass. The
// including shader declares the block Pass { DdgiParams pass; }. Each probe sits at its grid point plus
// its offset, and with pass.relocate a probe classified inside geometry is left out (probeStates: xyz
// the offset, w 1 for an active probe; the relocation pass, relocate.comp.glsl, writes them).
#include "shared/octahedral.glsl"
layout(binding = TEXUNIT_PASS_INPUT) uniform sampler2D uProbeIrradiance;  // RGBA32F atlas, rgb = E / π
layout(binding = TEXUNIT_PASS_INPUT2) uniform sampler2D uProbeDistance;   // RG32F atlas: mean d, d²

layout(std430, binding = BINDING_DDGI_PROBES) readonly buffer DdgiProbes { vec4 probeStates[]; };

int probeIndex(ivec3 i) { return i.x + pass.counts.x * (i.y + pass.counts.y * i.z); }
vec3 probePosition(ivec3 i) { return pass.origin.xyz + vec3(i) * pass.spacing.xyz + probeStates[probeIndex(i)].xyz; }

// Where direction d lies in probe p's tile of an atlas of `tile`-texel tiles (texture coordinates).
vec2 probeUv(int p, vec3 d, int tile, vec2 atlasSize) {
  vec2 corner = vec2(float(p % pass.counts.w), float(p / pass.counts.w)) * float(tile);
  vec2 inner = (octEncode(d) * 0.5f + 0.5f) * float(tile - 2);
  return (corner + 1.0f + inner) / atlasSize;
}

vec3 probeIrradiance(vec3 X, vec3 n, vec3 v) {
  vec3 rel = (X - pass.origin.xyz) / pass.spacing.xyz;
  ivec3 base = clamp(ivec3(floor(rel)), ivec3(0), max(pass.counts.xyz - 2, ivec3(0)));
  vec3 alpha = clamp(rel - vec3(base), vec3(0.0f), vec3(1.0f));
  vec2 irrSize = vec2(textureSize(uProbeIrradiance, 0)), distSize = vec2(textureSize(uProbeDistance, 0));
  vec3 Xb = X + (0.2f * n + 0.8f * v) * pass.origin.w;
  vec3 sum = vec3(0.0f);
  float total = 0.0f;
  for (int c = 0; c < 8; ++c) {
    ivec3 off = ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
    ivec3 idx = min(base + off, pass.counts.xyz - 1);
    int p = probeIndex(idx);
    if (probeStates[p].w == 0.0f) continue;  // inside geometry (classified by the relocation pass)
    vec3 P = probePosition(idx);
    vec3 tri = mix(vec3(1.0f) - alpha, alpha, vec3(off));
    vec3 toProbe = normalize(P - X);
    float b = (dot(toProbe, n) + 1.0f) * 0.5f;
    float w = b * b + 0.2f;
    vec3 fromProbe = Xb - P;
    float r = length(fromProbe);
    vec2 m = texture(uProbeDistance, probeUv(p, fromProbe / max(r, 1e-30f), DDGI_DISTANCE_TILE, distSize)).xy;
    if (r > m.x) {
      float variance = abs(m.x * m.x - m.y);
      float d = r - m.x;
      float chebyshev = variance / (variance + d * d);
      w *= chebyshev * chebyshev * chebyshev;
    }
    w = max(w, 1e-6f);
    if (w < 0.2f) w *= w * w / (0.2f * 0.2f);
    w *= tri.x * tri.y * tri.z;
    sum += w * texture(uProbeIrradiance, probeUv(p, n, DDGI_IRRADIANCE_TILE, irrSize)).xyz;
    total += w;
  }
  return total > 0.0f ? sum / total : vec3(0.0f);
}
