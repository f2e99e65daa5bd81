// The screen-space gather kit (illum/kits/gather_kit.h) that hemisphere-gathering
// modules share (nearfield, voxel_ao): a low-resolution gather buffer, its
// interleaved direction sets, the geometry-aware blur and the joint bilateral
// upsampling. This header holds what its passes share: the full-resolution
// G-buffer, the scale (image pixels per gather pixel), the representative
// image texel of each gather pixel, the geometry-aware weights — a neighbour
// counts when its surface lies on the receiver's tangent plane (distance along
// the receiver's normal, relative to the world size of a pixel there) and
// faces the same way — and (GATHER_DIRECTIONS) the direction of ray r.
//
// Interleaved sampling (Keller and Heidrich 2001): the pixels of a k×k block
// use k² different sets of N directions, which together stratify the
// hemisphere (Hammersley over k²·N points, rotated per sample and per block,
// so the pattern does not repeat with the block period); the blur afterwards
// averages them. Every set alone spans the hemisphere (shared/sampling.glsl),
// so a blur window that loses some sets at an edge loses samples, not azimuths.
#include "shared/gbuffer.glsl"
#include "shared/sampling.glsl"
uniform int uScale;  // 1, 2 or 4

// The image texel an indirect pixel stands for.
ivec2 representative(ivec2 q, ivec2 full) { return min(q * uScale + uScale / 2, full - 1); }

// A gather pass runs in dispatches over batches of its items (rays, VPL
// chains): items uBatchFirst … uBatchEnd − 1, added to what the earlier
// dispatches of the sample stored (uAccumulate). llvmpipe ends every loop of
// an invocation once 65535 loop iterations have run in it in all (gallivm's
// loop limiter counts the whole invocation), which one pass over 256 rays of
// a few hundred tracer steps each reaches — the rest were silently dropped.
uniform int uBatchFirst, uBatchEnd, uAccumulate;
// What the earlier dispatches stored at q of the pass's rgba32f image (a macro: image formats do not pass).
#define gatheredBefore(img, q) (uAccumulate != 0 ? imageLoad(img, q) : vec4(0.0f))

// The surface gather pixel q stands for (its representative image pixel's):
// false where no surface was seen there (the pass stores 0).
bool gatherReceiver(ivec2 q, out vec3 p, out vec3 n) {
  ivec2 px = representative(q, textureSize(gPosition, 0));
  vec4 P = texelFetch(gPosition, px, 0);
  p = P.xyz;
  n = P.w != 0.0f ? normalize(texelFetch(gNormal, px, 0).xyz) : vec3(0.0f, 0.0f, 1.0f);
  return P.w != 0.0f;
}

uniform vec3 uCameraPosition;
uniform float uPixelAngle;   // world size of one full-resolution pixel per unit distance

float geometryWeight(vec3 p, vec3 n, vec3 pj, vec3 nj, float pixels) {
  float plane = abs(dot(pj - p, n));
  float scale = uPixelAngle * distance(p, uCameraPosition) * pixels;
  float wn = max(dot(n, nj), 0.0f);
  wn *= wn;
  wn *= wn;  // cos⁴
  float wp = exp(-(plane * plane) / max(scale * scale, 1e-30f));
  return wn * wp;
}

#ifdef GATHER_DIRECTIONS
uniform int uRays;        // N
uniform int uInterleave;  // k
uniform vec2 uRotation;   // per-sample Cranley–Patterson rotation
uniform int uFrame;       // the sample index: each interleave block adds its own rotation

// The cosine-distributed direction of ray r of gather pixel q around `frame`.
vec3 gatherDirection(ivec2 q, int r, Basis frame) {
  uint set = uint(q.x % uInterleave + uInterleave * (q.y % uInterleave));
  vec2 rotation = uRotation + blockRotation(uint(q.x / uInterleave), uint(q.y / uInterleave), uint(uFrame));
  vec2 u = fract(interleavedSample(uint(r), set, uint(uRays), uint(uInterleave * uInterleave)) + rotation);
  return basisToWorld(frame, cosineSampleHemisphere(u));
}
#endif
