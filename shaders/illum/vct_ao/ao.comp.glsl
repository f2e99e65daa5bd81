// vct_ao's gather (illum/methods/vct_ao.cpp; Basgier 2015 §5.2, §6.3.1): per gather
// pixel the constellation cones (tangent-space axes aligned to the normal and
// the tangent frame, w = each axis' cosine-weighted share, Σ w = 1), turned
// about the normal by turn (per sample) plus, with jitter, a per-pixel
// pseudo-random azimuth (the thesis' local jitter: neighbouring pixels never
// launch the same cones); each cone from p + offset·n up to radius through
// the opacity volume (cones.glsl), its occlusion weakened by 1/(1 + λ t/r).
// AO = Σ w_k (1 − occlusion_k). Output: rgb = AO, w = 1 on a surface.
#include "illum/vct/cones.glsl"
#include "illum/gather/gather_pass.glsl"
#include "params.glsl"
layout(rgba32f, binding = IMAGE_OUTPUT) uniform image2D uAo;
layout(std140, binding = UBO_PASS) uniform Pass { VctAoParams pass; };

ivec2 gatherSize() { return imageSize(uAo); }

void gatherEmpty(ivec2 q) {
  imageStore(uAo, q, vec4(0.0f));
}

void gatherPixel(ivec2 q, vec3 p, vec3 n) {
  float jitter = pass.jitter * uintToUnitFloat(rngSeed(uint(q.x), uint(q.y), pass.seed));
  Basis frame = turnedBasis(n, pass.turn + jitter);
  vec3 apex = p + n * pass.offset;
  float ao = 0.0f;
  for (int k = gather.batchFirst; k < gather.batchEnd; ++k) {
    vec3 d = normalize(basisToWorld(frame, vec3(pass.cones[k].x, pass.cones[k].y, pass.cones[k].z)));
    ConeResult c = traceCone(apex, d, pass.tanHalf, pass.radius, pass.radius, pass.falloff, false, pass.offset, pass.guard != 0 ? dot(d, n) : -1.0f);
    ao += pass.cones[k].w * (1.0f - c.occlusion);
  }
  imageStore(uAo, q, vec4(vec3(gatheredBefore(uAo, q).x + ao), 1.0f));
}
