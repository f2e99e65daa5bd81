// vct's injection, a moving frame: the sums of the cells it injects again
// (uFirstCell … uEndCell − 1: those a moving mesh and its shadow changed;
// inject_sums.glsl, INJECT_REGION) set to 0 — counts, radiance, the per-cell
// maximum and, INJECT_DIRECTIONAL, the direction sums — so the region's pass
// adds into what a fresh fill starts from; every other cell keeps its sums.
#include "shared/value_grid.glsl"
#include "shared/bindings.glsl"
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
uniform uvec4 uResolution;
uniform uvec3 uFirstCell;
uniform uvec3 uEndCell;
layout(std430, binding = BINDING_VALUE_COUNTS) writeonly buffer Counts { uint counts[]; };
layout(std430, binding = BINDING_VALUE_RADIANCE) writeonly buffer RadianceSums { uint radianceSums[]; };
layout(std430, binding = BINDING_INJECT_CELL_MAX) writeonly buffer CellMax { uint cellMaxBits[]; };
#ifdef INJECT_DIRECTIONAL
layout(std430, binding = BINDING_VALUE_DIRECTION) writeonly buffer DirectionSums { uint directionSums[]; };
#endif
void main() {
  uvec3 cell = gl_GlobalInvocationID + uFirstCell;
  if (any(greaterThanEqual(cell, uEndCell))) return;
  uint slot = valueIndex(cell, uResolution, 0u) / 4u;
  counts[slot] = 0u;
  cellMaxBits[slot] = 0u;
  for (uint k = 0u; k < 4u; ++k) {
    radianceSums[4u * slot + k] = 0u;
#ifdef INJECT_DIRECTIONAL
    directionSums[4u * slot + k] = 0u;
#endif
  }
}
