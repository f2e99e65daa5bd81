// Geometry-aware blur of the indirect buffer over a (2k−1)×(2k−1) tent
// window (k the interleave block), so each pixel averages the k² direction
// sets of its neighbourhood with equal weight — but only from neighbours on
// its own surface (depth along the normal, normal similarity), which keeps
// indirect shadows and corners sharp.
#include "gather.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = TEXUNIT_PASS_INPUT) uniform sampler2D uInput;
layout(rgba32f, binding = IMAGE_OUTPUT) uniform writeonly image2D uOutput;

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(uOutput);
  if (q.x >= size.x || q.y >= size.y) return;
  vec4 c = texelFetch(uInput, q, 0);
  if (c.w == 0.0f) {
    imageStore(uOutput, q, vec4(0.0f));
    return;
  }
  ivec2 full = textureSize(gPosition, 0);
  ivec2 px = representative(q, full);
  vec3 p = texelFetch(gPosition, px, 0).xyz;
  vec3 n = texelFetch(gNormal, px, 0).xyz;
  vec3 sum = vec3(0.0f);
  float wsum = 0.0f;
  // Tent weights (k − |dx|)(k − |dy|) over −(k−1) … k−1: they sum to the
  // same total on every k-periodic lattice, so each direction set still
  // counts equally on a flat surface, and one bright ray spreads as a soft
  // bump instead of a hard k×k square (visible at 1 spp).
  int k = gather.interleave;
  for (int dy = 1 - k; dy <= k - 1; ++dy)
    for (int dx = 1 - k; dx <= k - 1; ++dx) {
      ivec2 qj = q + ivec2(dx, dy);
      if (qj.x < 0 || qj.y < 0 || qj.x >= size.x || qj.y >= size.y) continue;
      vec4 cj = texelFetch(uInput, qj, 0);
      if (cj.w == 0.0f) continue;
      ivec2 pj = representative(qj, full);
      float w = float((k - abs(dx)) * (k - abs(dy))) * geometryWeight(p, n, texelFetch(gPosition, pj, 0).xyz, texelFetch(gNormal, pj, 0).xyz,
                               float(gather.scale));
      sum += w * cj.xyz;
      wsum += w;
    }
  // The centre always has weight k² > 0.
  imageStore(uOutput, q, vec4(sum / wsum, 1.0f));
}
