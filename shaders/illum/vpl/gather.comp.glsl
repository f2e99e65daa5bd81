// The VPL gather (VGI §5.3; deferred and interleaved, Keller and Heidrich
// 2001), one invocation per gather pixel q of the gather kit's buffer
// (illum/gather_kit.h): the surface of q's representative image pixel
// gathers from the chains of its interleave subset (shared/vpl.glsl:
// vplSubset — chains i ≡ s mod k², each weighted k²), every bounce of each.
// Visibility (uVisibility): 1 the two-point test of VGI §4.1 through the
// voxel grid (traverse/tracer.glsl: visibleBetween) between the receiver and
// the VPL, each moved uOffset along its normal out of its own voxel; 0 none
// (every VPL is seen: the AVG paper's "without visibility" rows). The kit's
// blur then averages the k² subsets over each k×k window, and its upsampling
// composites albedo × the gathered value into the sample.
// One dispatch visits the subset's chains uBatchFirst … uBatchEnd − 1 (in
// subset order; the kit's batches: gather.glsl).
#include "../gather/gather.glsl"
#include "../../shared/vpl.glsl"
#include "../../traverse/tracer.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = IMAGE_OUTPUT) uniform image2D uGathered;
layout(std430, binding = BINDING_VPLS) readonly buffer Vpls { Vpl vpls[]; };
uniform uint uChains;       // N
uniform int uBounces;       // VPLs per chain
uniform int uInterleave;    // k
uniform float uMinDistance2; // the clamp: d² ≥ this in the geometry term
uniform int uVisibility;    // 0 none, 1 voxels
uniform float uOffset;      // the two-point test's offset along each normal, world units

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(uGathered);
  if (q.x >= size.x || q.y >= size.y) return;
  ivec2 px = representative(q, textureSize(gPosition, 0));
  vec4 P = texelFetch(gPosition, px, 0);
  if (P.w == 0.0f) {
    imageStore(uGathered, q, vec4(0.0f));
    return;
  }
  vec3 p = P.xyz;
  vec3 n = normalize(texelFetch(gNormal, px, 0).xyz);
  vec3 a = p + n * uOffset;
  uint sets = uint(uInterleave * uInterleave);
  vec3 sum = vec3(0.0f);
  uint s = vplSubset(q, uInterleave), end = min(uChains, s + uint(uBatchEnd) * sets);
  for (uint i = s + uint(uBatchFirst) * sets; i < end; i += sets) {
    for (int b = 0; b < uBounces; ++b) {
      Vpl v = vpls[uint(b) * uChains + i];
      if (v.position.w == 0.0f) break;
      vec3 c = vplGather(v, p, n, uMinDistance2);
      bool seen = c != vec3(0.0f);
      if (seen && uVisibility != 0) seen = visibleBetween(a, v.position.xyz + v.normal.xyz * uOffset);
      if (seen) sum += c;
    }
  }
  imageStore(uGathered, q, vec4(gatheredBefore(uGathered, q).xyz + sum * float(sets), 1.0f));
}
