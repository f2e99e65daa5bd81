#include "shared/voxel_grid.glsl"
in float vDepth;
uniform uvec4 uResolution;
#include "shared/bindings.glsl"
layout(std430, binding = BINDING_GRID_WORDS) buffer Columns { uint words[]; };
void main() {
  if (vDepth < 0.0f || vDepth > float(uResolution.z)) return;
  uint k = min(uint(vDepth), uResolution.z - 1u);
  uvec2 c = uvec2(gl_FragCoord.xy);
  atomicOr(words[columnWordIndex(c.x, c.y, depthWord(k), uResolution)], depthBit(k));
}
