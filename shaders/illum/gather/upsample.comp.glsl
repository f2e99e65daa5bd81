// Joint bilateral upsampling (Kopf et al. 2007) of the gather buffer to full
// resolution, and the composite: the full-resolution G-buffer guides the
// weights (bilinear × geometry) of the 4×4 nearest gather pixels. Composite
// gather.composite 0 (reflected light): albedo × E is added to the sample's direct
// light (uSample, written by the direct pass); 1 (a value such as AO): the
// sample is E itself (0 where no surface was seen). Where no neighbour lies on the
// pixel's surface (thin features under ¼ resolution), the geometrically
// closest one is used. The indirect and the direct parts alone go to the
// output channels when asked for (gather.writeIndirect, gather.writeDirect).
#include "gather.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = TEXUNIT_PASS_INPUT) uniform sampler2D uInput;
layout(rgba32f, binding = IMAGE_SAMPLE) uniform image2D uSample;
layout(rgba32f, binding = IMAGE_SAMPLE_AOV0) uniform writeonly image2D uIndirectAov;
layout(rgba32f, binding = IMAGE_SAMPLE_AOV1) uniform writeonly image2D uDirectAov;

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  ivec2 full = imageSize(uSample);
  if (px.x >= full.x || px.y >= full.y) return;
  vec4 P = texelFetch(gPosition, px, 0);
  vec4 direct = gather.composite == 0 ? imageLoad(uSample, px) : vec4(0.0f, 0.0f, 0.0f, 1.0f);
  if (gather.writeDirect != 0) imageStore(uDirectAov, px, direct);
  if (P.w == 0.0f) {
    if (gather.writeIndirect != 0) imageStore(uIndirectAov, px, vec4(0.0f, 0.0f, 0.0f, 1.0f));
    if (gather.composite != 0) imageStore(uSample, px, vec4(0.0f, 0.0f, 0.0f, 1.0f));
    return;
  }
  vec3 p = P.xyz;
  vec3 n = texelFetch(gNormal, px, 0).xyz;
  ivec2 low = textureSize(uInput, 0);
  vec3 E = vec3(0.0f);
  if (gather.scale == 1) {
    E = texelFetch(uInput, px, 0).xyz;
  } else {
    // Position of this pixel in indirect-pixel units (representatives sit at q·s + s/2).
    vec2 u = (vec2(px) - float(gather.scale / 2)) / float(gather.scale);
    ivec2 base = ivec2(floor(u));
    vec3 sum = vec3(0.0f), best = vec3(0.0f);
    float wsum = 0.0f, bestW = -1.0f;
    for (int dy = -1; dy <= 2; ++dy)
      for (int dx = -1; dx <= 2; ++dx) {
        ivec2 q = base + ivec2(dx, dy);
        if (q.x < 0 || q.y < 0 || q.x >= low.x || q.y >= low.y) continue;
        vec4 c = texelFetch(uInput, q, 0);
        if (c.w == 0.0f) continue;
        ivec2 rp = representative(q, full);
        float g = geometryWeight(p, n, texelFetch(gPosition, rp, 0).xyz, texelFetch(gNormal, rp, 0).xyz, 1.0f);
        vec2 d = abs(vec2(q) - u);
        float bilinear = max(1.0f - d.x, 0.0f) * max(1.0f - d.y, 0.0f);
        sum += bilinear * g * c.xyz;
        wsum += bilinear * g;
        if (g > bestW) {
          bestW = g;
          best = c.xyz;
        }
      }
    E = wsum > 1e-6f ? sum / wsum : best;
  }
  vec3 indirect = gather.composite == 0 ? texelFetch(gAlbedo, px, 0).xyz * E : E;
  imageStore(uSample, px, vec4(direct.xyz + indirect, 1.0f));
  if (gather.writeIndirect != 0) imageStore(uIndirectAov, px, vec4(indirect, 1.0f));
}
