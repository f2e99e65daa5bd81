// Joint bilateral upsampling (Kopf et al. 2007) of the gather buffer to full
// resolution, and the composite: the full-resolution G-buffer guides the
// weights (bilinear × geometry) of the 4×4 nearest gather pixels. Composite
// gather.composite 0 (reflected light): albedo × E is added to the sample's direct
// light (uSample, written by the direct pass); 1 (a value such as AO): the
// sample is E itself (0 where no surface was seen). Where no neighbour lies on the
// pixel's surface (thin features under ¼ resolution), the geometrically
// closest one is used — or, with GATHER_FIXUP, the pixel's own full-rate
// gather (gather.glsl), which the same code run with GATHER_FIXUP_LIST lists.
// The indirect and the direct parts alone go to the output channels when asked
// for (gather.writeIndirect, gather.writeDirect).
#include "gather.glsl"
#include "visibility.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = TEXUNIT_PASS_INPUT) uniform sampler2D uInput;
#ifndef GATHER_FIXUP_LIST
layout(rgba32f, binding = IMAGE_SAMPLE) uniform image2D uSample;
layout(rgba32f, binding = IMAGE_SAMPLE_AOV0) uniform writeonly image2D uIndirectAov;
layout(rgba32f, binding = IMAGE_SAMPLE_AOV1) uniform writeonly image2D uDirectAov;
#endif
#ifdef GATHER_FIXUP
layout(binding = TEXUNIT_GATHER_FIXUP) uniform sampler2D uFixup;
#endif

// E at image pixel px (surface p, n) from the gather buffer; false where no neighbour on the
// pixel's surface carried weight (E is then the fallback).
bool upsampled(ivec2 px, vec3 p, vec3 n, ivec2 full, out vec3 E) {
  ivec2 low = textureSize(uInput, 0);
  if (gather.scale == 1) {
    E = texelFetch(uInput, px, 0).xyz;
    return true;
  }
  // Position of this pixel in indirect-pixel units (representatives sit at q·s + s/2).
  vec2 u = (vec2(px) - float(gather.scale / 2)) / float(gather.scale);
  ivec2 base = ivec2(floor(u));
  // sum / wsum: the neighbours on the pixel's surface; seen / wseen: those of them in its room
  // (GATHER_VISIBILITY: the gather pixel nearest it and those of the 2×2 around it — the only ones
  // with a bilinear weight — that the edge mask connects to that one, no trace of its own). Where
  // that leaves none, all count; where none lies on its surface at all, the closest one's light is
  // used, or (GATHER_FIXUP) the pixel is gathered again — as where a wall splits the 2×2 and the
  // pixel is not on the nearest one's surface.
  vec3 sum = vec3(0.0f), seen = vec3(0.0f), best = vec3(0.0f);
  float wsum = 0.0f, wseen = 0.0f, bestW = -1.0f, gNearest = 0.0f;
#ifdef GATHER_VISIBILITY
  uint reach = 0u;                      // bit x + 2y: that pixel of the 2×2 from base
  ivec2 o = ivec2(round(u)) - base;  // the nearest, (0|1, 0|1)
  if (inGather(base, low) && inGather(base + ivec2(1), low)) {
    ivec2 h = ivec2(1 - o.x, o.y), v = ivec2(o.x, 1 - o.y), d = ivec2(1 - o.x, 1 - o.y);
    bool rh = gatherEdgeOpen(base + ivec2(0, o.y), 0), rv = gatherEdgeOpen(base + ivec2(o.x, 0), 1);
    bool rd = (rh && gatherEdgeOpen(base + ivec2(h.x, 0), 1)) || (rv && gatherEdgeOpen(base + ivec2(0, v.y), 0));
    reach = (1u << uint(o.x + 2 * o.y)) | (rh ? 1u << uint(h.x + 2 * h.y) : 0u) |
            (rv ? 1u << uint(v.x + 2 * v.y) : 0u) | (rd ? 1u << uint(d.x + 2 * d.y) : 0u);
  }
#endif
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
#ifdef GATHER_VISIBILITY
      if (ivec2(dx, dy) == o) gNearest = g;
      if (dx < 0 || dy < 0 || dx > 1 || dy > 1 || (reach & (1u << uint(dx + 2 * dy))) == 0u) continue;
#endif
      seen += bilinear * g * c.xyz;
      wseen += bilinear * g;
    }
  E = wseen > 1e-6f ? seen / wseen : (wsum > 1e-6f ? sum / wsum : best);
#ifdef GATHER_VISIBILITY
  // A wall splits the 2×2 and the pixel is not on its nearest gather pixel's surface: it may be the
  // wall itself (its face, seen between the two rooms), whose light is neither room's.
  if (reach != 15u && gNearest < 0.5f) return false;
#endif
  return wsum > 1e-6f;
}

#ifdef GATHER_FIXUP_LIST
void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  ivec2 full = textureSize(gPosition, 0);
  if (px.x >= full.x || px.y >= full.y) return;
  vec4 P = texelFetch(gPosition, px, 0);
  if (P.w == 0.0f) return;
  vec3 E;
  if (!upsampled(px, P.xyz, texelFetch(gNormal, px, 0).xyz, full, E)) {
    uint i = atomicAdd(fixupCount, 1u);
    fixupPixels[i] = uint(px.x) | (uint(px.y) << 16u);
    atomicMax(fixupGroups[0], i / 64u + 1u);
  }
}
#else
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
  vec3 E;
  upsampled(px, P.xyz, texelFetch(gNormal, px, 0).xyz, full, E);
#ifdef GATHER_FIXUP
  vec4 own = texelFetch(uFixup, px, 0);  // this pixel's full-rate gather, where it was listed
  if (own.w != 0.0f) E = own.xyz;
#endif
  vec3 indirect = gather.composite == 0 ? texelFetch(gAlbedo, px, 0).xyz * E : E;
  imageStore(uSample, px, vec4(direct.xyz + indirect, 1.0f));
  if (gather.writeIndirect != 0) imageStore(uIndirectAov, px, vec4(indirect, 1.0f));
}
#endif
