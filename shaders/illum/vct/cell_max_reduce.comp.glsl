// vct's injection, a moving frame: the largest radiance of any (triangle, cell)
// pair — the fixed-point range a fresh fill would take (its first pass) — as the
// largest of the per-cell maxima (inject_sums.glsl, INJECT_CELL_MAX): the cells
// injected again hold this frame's, every other cell the same pairs' as before.
// Non-negative floats order as their bits, so the maximum is exact.
#include "shared/bindings.glsl"
layout(local_size_x = 64) in;
uniform uint uCells;
layout(std430, binding = BINDING_INJECT_CELL_MAX) readonly buffer CellMax { uint cellMaxBits[]; };
layout(std430, binding = BINDING_VALUE_RADIANCE_MAX) buffer RadianceMax { uint radianceMaxBits; };
shared uint groupMax[64];
void main() {
  // Each invocation takes every (invocations)-th cell from its own: neighbours read neighbours.
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x, m = 0u;
  for (uint i = gl_GlobalInvocationID.x; i < uCells; i += stride) m = max(m, cellMaxBits[i]);
  groupMax[gl_LocalInvocationIndex] = m;
  barrier();
  for (uint s = 32u; s > 0u; s >>= 1u) {
    if (gl_LocalInvocationIndex < s)
      groupMax[gl_LocalInvocationIndex] = max(groupMax[gl_LocalInvocationIndex], groupMax[gl_LocalInvocationIndex + s]);
    barrier();
  }
  if (gl_LocalInvocationIndex == 0u && groupMax[0] > 0u) atomicMax(radianceMaxBits, groupMax[0]);
}
