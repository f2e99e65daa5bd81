// vct's diffuse cones (illum/methods/vct.cpp; Dinse 2015 §3.3), a gather pass of the
// kit (../gather/gather.glsl) at 1, ½ or ¼ resolution: per gather pixel the
// constellation uCones (tangent-space axes, w = the axis' share of the
// cosine-weighted hemisphere, Σ w = 1) turned by uTurn about the normal, each
// cone from the apex p + uOffset·n; the gather buffer receives
// E = Σ w_k L_k (L_r = ρ E: the kit's composite multiplies the albedo in),
// the second output the AO Σ w_k (1 − occlusion_k) within uAoRadius.
// Cones uBatchFirst … uBatchEnd − 1 of the dispatch (the kit's batching).
#include "../../shared/constants.glsl"
#include "../../shared/sampling.glsl"
#include "../../shared/brdf.glsl"
#include "../../shared/environment.glsl"
#include "../../shared/gpu_scene.glsl"
#include "cones.glsl"
#include "../gather/gather.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
uniform int uGuard;  // cones.glsl's receiver guard
layout(rgba32f, binding = IMAGE_OUTPUT) uniform image2D uIndirect;
layout(rgba32f, binding = IMAGE_OUTPUT2) uniform image2D uAoLow;
uniform vec4 uCones[16];
uniform float uTanHalf;      // the diffuse cones' tan(aperture / 2)
uniform float uMaxDistance;  // a cone's length, world units
uniform float uOffset;       // apex offset along the normal, world units
uniform float uAoRadius;     // AO: occlusion counts within this distance
uniform float uFalloff;      // AO: λ of 1/(1 + λ t / radius)
uniform float uTurn;         // the constellation's azimuth this sample
uniform float uSetTurn;      // … plus this per interleave set (k×k blocks, the kit's blur averages them)
uniform int uSets;           // k
uniform int uEnv;            // cones leaving the grid see the environment
uniform float uDiffuse;      // 1, or 0 with diffuse=false (the cones then give the AO alone)

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(uIndirect);
  if (q.x >= size.x || q.y >= size.y) return;
  vec3 p, n;
  if (!gatherReceiver(q, p, n)) {
    imageStore(uIndirect, q, vec4(0.0f));
    imageStore(uAoLow, q, vec4(0.0f));
    return;
  }
  int set = q.x % uSets + uSets * (q.y % uSets);
  Basis frame = turnedBasis(n, uTurn + uSetTurn * float(set));
  vec3 apex = p + n * uOffset;
  vec3 E = vec3(0.0f);
  float ao = 0.0f;
  for (int k = uBatchFirst; k < uBatchEnd; ++k) {
    vec3 d = normalize(basisToWorld(frame, vec3(uCones[k].x, uCones[k].y, uCones[k].z)));
    ConeResult c = traceCone(apex, d, uTanHalf, uMaxDistance, uAoRadius, uFalloff, false, uOffset, uGuard != 0 ? dot(d, n) : -1.0f);
    vec3 L = c.radiance;
    if (uEnv != 0 && c.escaped > 0.0f) L += (1.0f - c.opacity) * gpuEnvironmentRadiance(d);
    E += uCones[k].w * L;
    ao += uCones[k].w * (1.0f - c.occlusion);
  }
  imageStore(uIndirect, q, vec4(gatheredBefore(uIndirect, q).xyz + uDiffuse * E, 1.0f));
  imageStore(uAoLow, q, vec4(vec3(gatheredBefore(uAoLow, q).x + ao), 1.0f));
}
