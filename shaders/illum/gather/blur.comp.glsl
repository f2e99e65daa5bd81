// Geometry-aware blur of the indirect buffer over a (2k−1)×(2k−1) tent
// window (k the interleave block), so each pixel averages the k² direction
// sets of its neighbourhood with equal weight — but only from neighbours on
// its own surface (depth along the normal, normal similarity), which keeps
// indirect shadows and corners sharp.
#include "gather.glsl"
#include "visibility.glsl"
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
#ifdef GATHER_VISIBILITY
  // Bit c0 + dx of reach[c0 + dy] (c0 = k − 1): the neighbour (dx, dy) is reached from q by open
  // edges (visibility.glsl), along x then y (first pass) or along y then x (second pass).
  uint reach[2 * kMaxInterleave - 1];
  int c0 = k - 1;
  uint row = 1u << uint(c0);  // the row through q: q itself, then outwards while the edges are open
  bool right = true, left = true;
  for (int dx = 1; dx <= c0; ++dx) {
    right = right && inGather(q + ivec2(dx, 0), size) && gatherEdgeOpen(q + ivec2(dx - 1, 0), 0);
    left = left && inGather(q - ivec2(dx, 0), size) && gatherEdgeOpen(q - ivec2(dx, 0), 0);
    if (right) row |= 1u << uint(c0 + dx);
    if (left) row |= 1u << uint(c0 - dx);
  }
  reach[c0] = row;
  for (int dy = 1; dy <= c0; ++dy) {
    uint up = 0u, down = 0u;
    for (int dx = -c0; dx <= c0; ++dx) {
      uint bit = 1u << uint(c0 + dx);
      ivec2 a = q + ivec2(dx, dy - 1), b = q + ivec2(dx, -dy);
      if ((reach[c0 + dy - 1] & bit) != 0u && inGather(a + ivec2(0, 1), size) && gatherEdgeOpen(a, 1)) up |= bit;
      if ((reach[c0 - dy + 1] & bit) != 0u && inGather(b, size) && gatherEdgeOpen(b, 1)) down |= bit;
    }
    reach[c0 + dy] = up;
    reach[c0 - dy] = down;
  }
  // y then x: the column through q, then along each row; a cell reached either way counts.
  bool colUp = true, colDown = true;
  for (int dy = 0; dy <= c0; ++dy) {
    if (dy > 0) {
      colUp = colUp && inGather(q + ivec2(0, dy), size) && gatherEdgeOpen(q + ivec2(0, dy - 1), 1);
      colDown = colDown && inGather(q - ivec2(0, dy), size) && gatherEdgeOpen(q - ivec2(0, dy), 1);
    }
    for (int side = 0; side < 2; ++side) {
      int y = side == 0 ? dy : -dy;
      if (!(side == 0 ? colUp : colDown)) continue;
      bool r = true, l = true;
      for (int dx = 1; dx <= c0; ++dx) {
        ivec2 a = q + ivec2(dx - 1, y), b = q + ivec2(-dx, y);
        r = r && inGather(a + ivec2(1, 0), size) && gatherEdgeOpen(a, 0);
        l = l && inGather(b, size) && gatherEdgeOpen(b, 0);
        if (r) reach[c0 + y] |= 1u << uint(c0 + dx);
        if (l) reach[c0 + y] |= 1u << uint(c0 - dx);
      }
    }
  }
#endif
  for (int dy = 1 - k; dy <= k - 1; ++dy)
    for (int dx = 1 - k; dx <= k - 1; ++dx) {
      ivec2 qj = q + ivec2(dx, dy);
      if (qj.x < 0 || qj.y < 0 || qj.x >= size.x || qj.y >= size.y) continue;
#ifdef GATHER_VISIBILITY
      if ((reach[dy + k - 1] & (1u << uint(dx + k - 1))) == 0u) continue;
#endif
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
