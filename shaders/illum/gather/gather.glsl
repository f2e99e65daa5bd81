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
#include "params.glsl"
layout(std140, binding = UBO_GATHER) uniform Gather { GatherParams gather; };

// The image texel an indirect pixel stands for.
ivec2 representative(ivec2 q, ivec2 full) { return min(q * gather.scale + gather.scale / 2, full - 1); }

// A gather pass runs in dispatches over batches of its items (rays, VPL
// chains): items gather.batchFirst … gather.batchEnd − 1, added to what the
// earlier dispatches of the sample stored (gather.accumulate). llvmpipe ends every loop of
// an invocation once 65535 loop iterations have run in it in all (gallivm's
// loop limiter counts the whole invocation), which one pass over 256 rays of
// a few hundred tracer steps each reaches — the rest were silently dropped.
// What the earlier dispatches stored at q of the pass's rgba32f image (a macro: image formats do not pass).
#define gatheredBefore(img, q) (gather.accumulate != 0 ? imageLoad(img, q) : vec4(0.0f))

// The surface gather pixel q stands for (its representative image pixel's):
// false where no surface was seen there (the pass stores 0).
bool gatherReceiver(ivec2 q, out vec3 p, out vec3 n) {
  ivec2 px = representative(q, textureSize(gPosition, 0));
  vec4 P = texelFetch(gPosition, px, 0);
  p = P.xyz;
  n = P.w != 0.0f ? normalize(texelFetch(gNormal, px, 0).xyz) : vec3(0.0f, 0.0f, 1.0f);
  return P.w != 0.0f;
}

float geometryWeight(vec3 p, vec3 n, vec3 pj, vec3 nj, float pixels) {
  float plane = abs(dot(pj - p, n));
  float scale = gather.camera.w * distance(p, gather.camera.xyz) * pixels;
  float wn = max(dot(n, nj), 0.0f);
  wn *= wn;
  wn *= wn;  // cos⁴
  float wp = exp(-(plane * plane) / max(scale * scale, 1e-30f));
  return wn * wp;
}

// GATHER_VISIBILITY: visibility.glsl (the blur, upsampling and edges passes include it).

// GATHER_FIXUP (the kit's `fixup`): an image pixel none of whose gather pixels lies on its surface
// (the upsampling would borrow the geometrically closest one's light: the front face of a thin wall
// takes a room's light behind it, a pole the wall's behind it) is listed by the upsampling's
// classifying run (GATHER_FIXUP_LIST) and gathered again at full rate, at the pixel itself, by the
// method's own gather pass compiled with GATHER_FIXUP (gather_pass.glsl); the upsampling then takes
// that value. The list's order follows the atomics, each entry's value only its pixel.
#if defined(GATHER_FIXUP) || defined(GATHER_FIXUP_LIST)
layout(std430, binding = BINDING_GATHER_FIXUP) buffer GatherFixup {
  uint fixupCount;
  uint fixupGroups[3];  // the fix-up run's glDispatchComputeIndirect: ⌈count / 64⌉, 1, 1
  uint fixupPixels[];   // x | y << 16
};
#endif

#ifdef GATHER_DIRECTIONS
// The cosine-distributed direction of ray r of gather pixel q around `frame`.
vec3 gatherDirection(ivec2 q, int r, Basis frame) {
  int k = gather.interleave;
  uint set = uint(q.x % k + k * (q.y % k));
  vec2 rotation = gather.rotation.xy + blockRotation(uint(q.x / k), uint(q.y / k), uint(gather.frame));
  vec2 u = fract(interleavedSample(uint(r), set, uint(gather.rays), uint(k * k)) + rotation);
  return basisToWorld(frame, cosineSampleHemisphere(u));
}
#endif
