// vct_ao's gather (illum/methods/vct_ao.cpp; Basgier 2015 §5.2, §6.3.1): per gather
// pixel the constellation uCones (tangent-space axes aligned to the normal and
// the tangent frame, w = each axis' cosine-weighted share, Σ w = 1), turned
// about the normal by uTurn (per sample) plus, with uJitter, a per-pixel
// pseudo-random azimuth (the thesis' local jitter: neighbouring pixels never
// launch the same cones); each cone from p + uOffset·n up to uRadius through
// the opacity volume (cones.glsl), its occlusion weakened by 1/(1 + λ t/r).
// AO = Σ w_k (1 − occlusion_k). Output: rgb = AO, w = 1 on a surface.
#include "../vct/cones.glsl"
#include "../gather/gather.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
uniform int uGuard;  // cones.glsl's receiver guard
layout(rgba32f, binding = IMAGE_OUTPUT) uniform image2D uAo;
uniform vec4 uCones[16];
uniform float uTanHalf;   // tan(aperture / 2), the overlap factor applied
uniform float uRadius;    // cone length r, world units
uniform float uOffset;    // origin offset along the normal, world units
uniform float uFalloff;   // λ
uniform float uTurn;      // the constellation's azimuth this sample
uniform float uJitter;    // the per-pixel azimuth's range (radians; 0: none)
uniform uint uSeed;

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(uAo);
  if (q.x >= size.x || q.y >= size.y) return;
  vec3 p, n;
  if (!gatherReceiver(q, p, n)) {
    imageStore(uAo, q, vec4(0.0f));
    return;
  }
  float jitter = uJitter * uintToUnitFloat(rngSeed(uint(q.x), uint(q.y), uSeed));
  Basis frame = turnedBasis(n, uTurn + jitter);
  vec3 apex = p + n * uOffset;
  float ao = 0.0f;
  for (int k = uBatchFirst; k < uBatchEnd; ++k) {
    vec3 d = normalize(basisToWorld(frame, vec3(uCones[k].x, uCones[k].y, uCones[k].z)));
    ConeResult c = traceCone(apex, d, uTanHalf, uRadius, uRadius, uFalloff, false, uOffset, uGuard != 0 ? dot(d, n) : -1.0f);
    ao += uCones[k].w * (1.0f - c.occlusion);
  }
  imageStore(uAo, q, vec4(vec3(gatheredBefore(uAo, q).x + ao), 1.0f));
}
