// The VPL gather (VGI §5.3; deferred and interleaved, Keller and Heidrich
// 2001), one invocation per gather pixel q of the gather kit's buffer
// (illum/kits/gather_kit.h): the surface of q's representative image pixel
// gathers from the chains of its interleave subset (shared/vpl.glsl:
// vplSubset — chains i ≡ s mod k², each weighted k²), every bounce of each.
// Visibility (pass.visibility, VPL_VISIBILITY_*): 1 the two-point test of VGI §4.1 through the
// voxel grid (traverse/tracer.glsl: visibleBetween) between the receiver and
// the VPL, each moved pass.offset along its normal out of its own voxel; 2 the
// VPL's shadow map in the atlas (vpl_shadow.glsl; `avg`), where a receiver
// outside the map (no visibility information) counts as seen; 0 none (every
// VPL is seen: the AVG paper's "without visibility" rows). The kit's
// blur then averages the k² subsets over each k×k window, and its upsampling
// composites albedo × the gathered value into the sample.
// One dispatch visits the subset's chains gather.batchFirst … gather.batchEnd − 1 (in
// subset order; the kit's batches: gather.glsl).
#include "illum/gather/gather_pass.glsl"
#include "shared/vpl.glsl"
#include "traverse/tracer.glsl"
#include "vpl_shadow.glsl"

layout(rgba32f, binding = IMAGE_OUTPUT) uniform image2D uGathered;
layout(std430, binding = BINDING_VPLS) readonly buffer Vpls { Vpl vpls[]; };
layout(std140, binding = UBO_PASS) uniform Pass { VplGatherParams pass; };
layout(binding = TEXUNIT_VPL_SHADOW) uniform sampler2D uVplShadow;

// The receiver p (normal n) against the VPL's map: lit unless the map saw a
// surface nearer than p by more than the slack (shared/vpl.glsl, vplShadowSlack):
// vplShadow.bias texels of the map's angular texel there (cube: 2/r; paraboloid:
// 2(1 + cos θ)/r, twice as coarse at its centre as at its rim) times the distance,
// plus the occluders' tolerance (illum/resources/occluders.h), over the receiver's cosine.
bool shadowMapSees(Vpl v, uint slot, vec3 p, vec3 n) {
  vec3 w = p - vplShadowCentre(v);
  float dist = length(w);
  int f = vplShadowCubeFaces() ? vplShadowFaceOf(vplShadowFrame(v, w)) : 0;
  // Behind a hemicube (a receiver within the lift of the VPL's plane, right under its centre) or a
  // paraboloid: nothing was drawn there.
  if (vplShadow.kind == VPL_MAP_HEMICUBE && f == 5) return true;
  vec4 c = vplShadowClip(v, f, w);
  if (c.w <= 0.0f || (vplShadow.kind == VPL_MAP_PARABOLOID && c.z <= 0.0f)) return true;
  vec2 uv = c.xy / c.w;
  ivec2 t = vplShadowFaceOrigin(slot, f) + clamp(ivec2(floor((uv * 0.5f + 0.5f) * float(vplShadow.res))), ivec2(0),
                                                 ivec2(vplShadow.res - 1));
  float stored = texelFetch(uVplShadow, t, 0).x * vplShadow.far;
  float texel = (vplShadowCubeFaces() ? 2.0f : 2.0f * (1.0f + c.z)) / float(vplShadow.res);
  float cosine = abs(dot(n, w)) / max(dist, 1e-30f);
  return dist - vplShadowSlack(vplShadow.bias, texel, dist, vplShadow.tolerance, cosine) <= stored;
}

ivec2 gatherSize() { return imageSize(uGathered); }

void gatherEmpty(ivec2 q) {
  imageStore(uGathered, q, vec4(0.0f));
}

void gatherPixel(ivec2 q, vec3 p, vec3 n) {
  vec3 a = p + n * pass.offset;
  uint sets = uint(gather.interleave * gather.interleave);
  vec3 sum = vec3(0.0f);
  uint s = vplSubset(q, gather.interleave), end = min(pass.chains, s + uint(gather.batchEnd) * sets);
  for (uint i = s + uint(gather.batchFirst) * sets; i < end; i += sets) {
    for (int b = 0; b < pass.bounces; ++b) {
      uint slot = uint(b) * pass.chains + i;
      Vpl v = vpls[slot];
      if (v.position.w == 0.0f) break;
      vec3 c = vplGather(v, p, n, pass.minDistance2);
      bool seen = c != vec3(0.0f);
      if (seen && pass.visibility == VPL_VISIBILITY_VOXELS) seen = visibleBetween(a, v.position.xyz + v.normal.xyz * pass.offset);
      if (seen && pass.visibility == VPL_VISIBILITY_SHADOW_MAPS) seen = shadowMapSees(v, slot, p, n);
      if (seen) sum += c;
    }
  }
  imageStore(uGathered, q, vec4(gatheredBefore(uGathered, q).xyz + sum * float(sets), 1.0f));
}
