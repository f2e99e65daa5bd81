// The gather's edge mask (GATHER_VISIBILITY, gather.glsl): per gather pixel q, bit 0 when q's surface
// and that of q + (1, 0) see each other through the method's voxels, bit 1 the same with q + (0, 1);
// 0 where either has no surface or lies outside.
#define GATHER_EDGES_PASS 1
#include "gather.glsl"
#include "visibility.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(r32ui, binding = IMAGE_OUTPUT) uniform writeonly uimage2D uEdges;

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(uEdges);
  if (q.x >= size.x || q.y >= size.y) return;
  ivec2 full = textureSize(gPosition, 0);
  vec3 p, n;
  uint bits = 0u;
  if (gatherReceiver(q, p, n)) {
    for (int axis = 0; axis < 2; ++axis) {
      ivec2 qj = q + (axis == 0 ? ivec2(1, 0) : ivec2(0, 1));
      if (!inGather(qj, size)) continue;
      vec3 pj, nj;
      if (gatherReceiver(qj, pj, nj) && gatherVisible(p, n, pj, nj)) bits |= 1u << uint(axis);
    }
  }
  imageStore(uEdges, q, uvec4(bits));
}
