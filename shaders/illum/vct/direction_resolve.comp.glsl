// vct's directional level 0 (`directional`; shared/value_grid.glsl:
// directionalFacing): per cell the direction its injected light leaves in, D,
// from the injection's direction sums (decodeDirection), written where the
// binary grid (the OR-mip pyramid's level 0, as value_resolve.comp's
// OCCUPANCY_FROM_GRID) holds the cell and 0 elsewhere — so a trilinear lookup
// over occupied and empty cells, divided by the occupancy it blends, is the
// occupancy-weighted mean D. Runs before the volume's mips: the anisotropic
// chain's first level reads it (voxelize/value_mip.comp, DIRECTIONAL).
#include "shared/value_grid.glsl"
#include "shared/bindings.glsl"
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
uniform uvec4 uResolution;
uniform uvec3 uFirstCell;  // the cells resolved: uFirstCell … uEndCell − 1 (all, or a changed box)
uniform uvec3 uEndCell;
layout(std430, binding = BINDING_VALUE_DIRECTION) readonly buffer DirectionSums { uint directionSums[]; };
layout(std430, binding = BINDING_PYRAMID) readonly buffer PyramidWords { uint pyramidWords[]; };
layout(rgba8_snorm, binding = IMAGE_VALUE_DIRECTION) uniform writeonly image3D oDirection;
void main() {
  uvec3 cell = gl_GlobalInvocationID + uFirstCell;
  if (any(greaterThanEqual(cell, uEndCell))) return;
  uint i = valueIndex(cell, uResolution, 0u);
  bool occupied =
      (pyramidWords[columnWordIndex(cell.x, cell.y, depthWord(cell.z), uResolution)] & depthBit(cell.z)) != 0u;
  vec3 d = occupied ? decodeDirection(uvec4(directionSums[i], directionSums[i + 1u], directionSums[i + 2u],
                                              directionSums[i + 3u]))
                    : vec3(0.0f);
  imageStore(oDirection, ivec3(cell), vec4(d, 0.0f));
}
