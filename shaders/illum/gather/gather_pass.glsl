// The gather pass's one entry (illum/kits/gather_kit.h): every gather shader — nearfield's indirect
// rays, ssdo's directions, voxel_ao's and vct_ao's AO, vct's diffuse cones, vpl's gather — runs this main() over its
// gather pixels q: nothing outside the output; where no surface was seen at q, gatherEmpty(q) (the
// pass stores 0 in its outputs); else gatherPixel(q, p, n) with the receiver's point and normal
// (gatherReceiver). The including shader declares its outputs and defines
//   ivec2 gatherSize();                         the size of the pass's output (all are one size)
//   void gatherEmpty(ivec2 q);
//   void gatherPixel(ivec2 q, vec3 p, vec3 n);
#include "illum/gather/gather.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

ivec2 gatherSize();
void gatherEmpty(ivec2 q);
void gatherPixel(ivec2 q, vec3 p, vec3 n);

#ifdef GATHER_FIXUP
// The fix-up run (gather.glsl): invocation i gathers at listed image pixel i, which stands for
// itself (its output is a full-resolution image); the kit dispatches ⌈count / 64⌉ groups.
void main() {
  uint i = gl_WorkGroupID.x * 64u + gl_LocalInvocationIndex;
  if (i >= fixupCount) return;
  ivec2 px = ivec2(int(fixupPixels[i] & 0xffffu), int(fixupPixels[i] >> 16u));
  vec4 P = texelFetch(gPosition, px, 0);
  gatherPixel(px, P.xyz, normalize(texelFetch(gNormal, px, 0).xyz));
}
#else
void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = gatherSize();
  if (q.x >= size.x || q.y >= size.y) return;
  vec3 p, n;
  if (!gatherReceiver(q, p, n)) {
    gatherEmpty(q);
    return;
  }
  gatherPixel(q, p, n);
}
#endif
