// vct's diffuse cones (illum/methods/vct.cpp; Dinse 2015 §3.3), a gather pass of the
// kit (../gather/gather.glsl) at 1, ½ or ¼ resolution: per gather pixel the
// constellation cones (tangent-space axes, w = the axis' share of the
// cosine-weighted hemisphere, Σ w = 1) turned by turn about the normal, each
// cone from the apex p + offset·n; the gather buffer receives
// E = Σ w_k L_k (L_r = ρ E: the kit's composite multiplies the albedo in),
// the second output the AO Σ w_k (1 − occlusion_k) within aoRadius.
// Cones gather.batchFirst … gather.batchEnd − 1 of the dispatch (the kit's batching).
// GATHER_FIXUP (the kit's `fixup`): the same cones at listed image pixels, the
// indirect light only (the AO keeps its upsampling there).
#include "shared/constants.glsl"
#include "shared/sampling.glsl"
#include "shared/brdf.glsl"
#include "shared/environment.glsl"
#include "shared/gpu_scene.glsl"
#include "cones.glsl"
#include "params.glsl"
#include "illum/gather/gather_pass.glsl"
layout(rgba32f, binding = IMAGE_OUTPUT) uniform image2D uIndirect;
layout(rgba32f, binding = IMAGE_OUTPUT2) uniform image2D uAoLow;
layout(std140, binding = UBO_PASS) uniform Pass { VctDiffuseParams pass; };

ivec2 gatherSize() { return imageSize(uIndirect); }

void gatherEmpty(ivec2 q) {
  imageStore(uIndirect, q, vec4(0.0f));
  imageStore(uAoLow, q, vec4(0.0f));
}

void gatherPixel(ivec2 q, vec3 p, vec3 n) {
  int set = q.x % pass.sets + pass.sets * (q.y % pass.sets);
  Basis frame = turnedBasis(n, pass.turn + pass.setTurn * float(set));
  vec3 apex = p + n * pass.offset;
  vec3 E = vec3(0.0f);
  float ao = 0.0f;
  for (int k = gather.batchFirst; k < gather.batchEnd; ++k) {
    vec3 d = normalize(basisToWorld(frame, vec3(pass.cones[k].x, pass.cones[k].y, pass.cones[k].z)));
    ConeResult c = traceCone(apex, d, pass.tanHalf, pass.maxDistance, pass.aoRadius, pass.falloff, false, pass.offset, pass.guard != 0 ? dot(d, n) : -1.0f);
    vec3 L = c.radiance;
    if (pass.env != 0 && c.escaped > 0.0f) L += (1.0f - c.opacity) * gpuEnvironmentRadiance(d);
    E += pass.cones[k].w * L;
    ao += pass.cones[k].w * (1.0f - c.occlusion);
  }
  imageStore(uIndirect, q, vec4(gatheredBefore(uIndirect, q).xyz + pass.diffuse * E, 1.0f));
#ifndef GATHER_FIXUP
  imageStore(uAoLow, q, vec4(vec3(gatheredBefore(uAoLow, q).x + ao), 1.0f));  // (fixed-up pixels: the AO's upsampling)
#endif
}
