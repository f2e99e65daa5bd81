// Geometry-aware blur of the indirect buffer over a k×k window (k the
// interleave block; offsets −⌊k/2⌋ … ⌈k/2⌉−1), so each pixel averages each of
// the k² direction sets of its neighbourhood exactly once — but only from neighbours on its own surface (depth along the
// normal, normal similarity), which keeps indirect shadows and corners sharp.
#include "indirect_buffer.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = TEXUNIT_PASS_INPUT) uniform sampler2D uInput;
layout(rgba32f, binding = 0) uniform writeonly image2D uOutput;
uniform int uInterleave;

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
  int lo = -(uInterleave / 2), hi = lo + uInterleave - 1;
  for (int dy = lo; dy <= hi; ++dy)
    for (int dx = lo; dx <= hi; ++dx) {
      ivec2 qj = q + ivec2(dx, dy);
      if (qj.x < 0 || qj.y < 0 || qj.x >= size.x || qj.y >= size.y) continue;
      vec4 cj = texelFetch(uInput, qj, 0);
      if (cj.w == 0.0f) continue;
      ivec2 pj = representative(qj, full);
      float w = geometryWeight(p, n, texelFetch(gPosition, pj, 0).xyz, texelFetch(gNormal, pj, 0).xyz,
                               float(uScale));
      sum += w * cj.xyz;
      wsum += w;
    }
  // The centre always has weight 1, so wsum ≥ 1.
  imageStore(uOutput, q, vec4(sum / wsum, 1.0f));
}
