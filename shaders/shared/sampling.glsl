// Sampling kernels shared by the GL modules and the CPU reference.
// Orthonormal basis: Duff et al., "Building an Orthonormal Basis, Revisited",
// JCGT 6(1), 2017 — branch on the sign of n.z so the basis stays accurate for
// normals near ±z (no cancellation in 1/(s + n.z)).
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
#include "constants.glsl"
SHARED_BEGIN

struct Basis {
  vec3 t;
  vec3 b;
  vec3 n;
};

SHARED_FN Basis makeBasis(vec3 n) {
  float s = n.z >= 0.0f ? 1.0f : -1.0f;
  float a = -1.0f / (s + n.z);
  float c = n.x * n.y * a;
  Basis f;
  f.t = vec3(1.0f + s * n.x * n.x * a, s * c, -s * n.x);
  f.b = vec3(c, s + n.y * n.y * a, -n.y);
  f.n = n;
  return f;
}

SHARED_FN vec3 basisToWorld(Basis f, vec3 v) { return f.t * v.x + f.b * v.y + f.n * v.z; }

// Base-2 radical inverse (van der Corput) of i, to 24 bits.
SHARED_FN float radicalInverse2(uint i) { return float(bitfieldReverse(i) >> 8u) * (1.0f / 16777216.0f); }

// Sample r of set s when `sets` sets of n samples share one stratified
// pattern (interleaved sampling, Keller and Heidrich 2001): u.x is point
// r·sets + s of a sets·n-stratification, u.y the radical inverse of s·n + r.
// Each set alone then covers both coordinates in n strata — so an average
// over only some sets (a blur window cut at an edge) is unbiased — and all
// sets together stratify u.x in sets·n strata. (The radical inverse of
// r·sets + s would give each set a 1/sets slice of u.y.)
SHARED_FN vec2 interleavedSample(uint r, uint s, uint n, uint sets) {
  return vec2((float(r * sets + s) + 0.5f) / float(n * sets), radicalInverse2(s * n + r));
}

// Cosine-distributed direction around +z from u in [0,1)²; pdf = cos θ / π.
// Malley's method; z is clamped so u.x → 1 (the horizon) never gives NaN.
SHARED_FN vec3 cosineSampleHemisphere(vec2 u) {
  float r = sqrt(u.x);
  float phi = 2.0f * PI * u.y;
  return vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0f, 1.0f - u.x)));
}

// Veach's power heuristic (Veach 1997, §9.2.4, β = 2): the MIS weight of a
// sample drawn with density pa when density pb could have drawn it too.
SHARED_FN float powerHeuristic(float pa, float pb) { return pa * pa / (pa * pa + pb * pb); }

// The probability that Russian roulette ends a path whose throughput is beta:
// 1 − its largest channel, at least 0.05 (the survivors are divided by 1 − q).
SHARED_FN float russianRouletteQ(vec3 beta) { return max(0.05f, 1.0f - max(beta.x, max(beta.y, beta.z))); }

// Direction in the cone of half-angle acos(cosMax) around +z, density ∝ cos^e.
SHARED_FN vec3 samplePowerCosine(vec2 u, float e) {
  float cosT = pow(max(u.x, 1e-30f), 1.0f / (e + 1.0f));
  float sinT = sqrt(max(0.0f, 1.0f - cosT * cosT));
  float phi = 2.0f * PI * u.y;
  return vec3(sinT * cos(phi), sinT * sin(phi), cosT);
}

// Random numbers, one 32-bit word of state per stream, the same in GLSL and
// C++ bit for bit: PCG's RXS-M-XS output on a 32-bit LCG (O'Neill 2014,
// "PCG: A family of simple fast space-efficient statistically good
// algorithms"; the 32-bit form of Jarzynski & Olano, "Hash Functions for GPU
// Rendering", JCGT 2020). A stream is seeded by hashing what identifies it
// (pixel, sample, seed: rngSeed) and stepped with pcgAdvance; each step's
// number is pcgOutput of the new state. Period 2³², enough for the few
// hundred numbers a path takes; a stream per pixel and sample keeps paths
// independent (the C++ reference keeps its 64-bit PCG32).
SHARED_FN uint pcgAdvance(uint state) { return state * 747796405u + 2891336453u; }
SHARED_FN uint pcgOutput(uint state) {
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}
// PCG hash: one step from v, as a hash of v.
SHARED_FN uint pcgHash(uint v) { return pcgOutput(pcgAdvance(v)); }

// The state of the stream identified by (a, b, c), e.g. pixel index, sample
// index, seed: nested hashes, so streams that differ in any word start apart.
SHARED_FN uint rngSeed(uint a, uint b, uint c) { return pcgHash(a ^ pcgHash(b ^ pcgHash(c))); }

// Uniform float in [0, 1) from the top 24 bits (exactly representable).
SHARED_FN float uintToUnitFloat(uint x) { return float(x >> 8u) * (1.0f / 16777216.0f); }

// Point i of Roberts' R2 sequence, frac(½ + i·(1/g, 1/g²)) with g the plastic
// number, shifted by the rotation (rx, ry) (Cranley–Patterson, mod 1) — in
// 32-bit fixed point (2³²/g = 3242174889, 2³²/g² = 2447445414, ½ = 2³¹), so
// GLSL and C++ agree at any index and float precision never runs out. Its
// 2D discrepancy is low for every prefix: what progressive per-sample choices
// (an emitter point per frame) need.
SHARED_FN vec2 r2Point(uint i, uint rx, uint ry) {
  uint x = i * 3242174889u + 2147483648u + rx;
  uint y = i * 2447445414u + 2147483648u + ry;
  return vec2(uintToUnitFloat(x), uintToUnitFloat(y));
}

// A Cranley–Patterson rotation for block (bx, by) of frame f: every k×k
// interleave block turns its k²·N directions by its own offset, so that one
// frame's pattern does not repeat with the block period (at 1 spp a repeated
// pattern shows through the blur as k×k patches); each block's sets still
// stratify the hemisphere together.
SHARED_FN vec2 blockRotation(uint bx, uint by, uint f) {
  uint h = pcgHash(bx * 0x8da6b343u ^ by * 0xd8163841u ^ f * 0xcb1ab31fu);
  return vec2(uintToUnitFloat(h), uintToUnitFloat(pcgHash(h)));
}

SHARED_END

// The next number in [0, 1) of stream `state` (pcgAdvance, then pcgOutput).
#ifdef __cplusplus
namespace vgi::shared {
inline float rngNext(glm::uint& state) {
  state = pcgAdvance(state);
  return uintToUnitFloat(pcgOutput(state));
}
}  // namespace vgi::shared
#else
float rngNext(inout uint state) {
  state = pcgAdvance(state);
  return uintToUnitFloat(pcgOutput(state));
}
#endif
