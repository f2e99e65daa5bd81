// One level of the OR-mip pyramid (VGI §4): each invocation ORs word w of the
// (up to) 2×2 child columns into its parent column. Index math shared with the
// CPU build (shaders/shared/or_mip.glsl).
#include "shared/voxel_grid.glsl"
#include "shared/or_mip.glsl"
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(std430, binding = BINDING_GRID_WORDS) buffer Pyramid { uint words[]; };
uniform uvec2 uSize;
uniform uvec2 uChildSize;
uniform uint uDepth;
uniform uint uOffset;
uniform uint uChildOffset;
void main() {
  uint x = gl_GlobalInvocationID.x, y = gl_GlobalInvocationID.y, w = gl_GlobalInvocationID.z;
  if (x >= uSize.x || y >= uSize.y) return;
  uint r = 0u;
  for (uint dy = 0u; dy < 2u; ++dy)
    for (uint dx = 0u; dx < 2u; ++dx)
      if (2u * x + dx < uChildSize.x && 2u * y + dy < uChildSize.y)
        r |= words[mipWordIndex(2u * x + dx, 2u * y + dy, w, uChildSize, uDepth, uChildOffset)];
  words[mipWordIndex(x, y, w, uSize, uDepth, uOffset)] = r;
}
