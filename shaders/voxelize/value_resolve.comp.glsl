// Multi-valued grids, resolve: per cell the mean of each built channel from the
// insertion's fixed-point sums (shared/value_grid.glsl: decodeValueMean, the
// CPU decode's own function), written into the channel's 3D texture (level 0),
// with the point count and the occupancy (1 where the cell has points).
// Channels compiled in: VALUE_NORMAL, VALUE_ALBEDO, VALUE_GLOSSY, VALUE_RADIANCE.
// The radiance texture is premultiplied: (L·α, α), α the occupancy (what cone
// tracing reads, Dinse 2015 §3.1). OCCUPANCY_FROM_GRID: α is the bit of a
// binary grid (the OR-mip pyramid's level 0 at BINDING_PYRAMID, any voxelizer
// of the registry) instead of count > 0; a cell without points or without
// the bit then holds 0 in every channel.
#include "shared/value_grid.glsl"
#include "shared/bindings.glsl"
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
uniform uvec4 uResolution;
uniform uvec3 uFirstCell;  // the cells resolved: uFirstCell … uEndCell − 1 (all, or a changed box)
uniform uvec3 uEndCell;
layout(std430, binding = BINDING_VALUE_COUNTS) readonly buffer Counts { uint counts[]; };
layout(r32ui, binding = IMAGE_VALUE_COUNT) uniform writeonly uimage3D oCount;
layout(r8, binding = IMAGE_VALUE_OCCUPANCY) uniform writeonly image3D oOccupancy;
#ifdef VALUE_NORMAL
layout(std430, binding = BINDING_VALUE_NORMAL) readonly buffer NormalSums { uint normalSums[]; };
layout(rgba16f, binding = IMAGE_VALUE_NORMAL) uniform writeonly image3D oNormal;
#endif
#ifdef VALUE_ALBEDO
layout(std430, binding = BINDING_VALUE_ALBEDO) readonly buffer AlbedoSums { uint albedoSums[]; };
layout(rgba8, binding = IMAGE_VALUE_ALBEDO) uniform writeonly image3D oAlbedo;
#endif
#ifdef VALUE_GLOSSY
layout(std430, binding = BINDING_VALUE_GLOSSY) readonly buffer GlossySums { uint glossySums[]; };
layout(rgba16f, binding = IMAGE_VALUE_GLOSSY) uniform writeonly image3D oGlossy;
#endif
#ifdef VALUE_RADIANCE
layout(std430, binding = BINDING_VALUE_RADIANCE) readonly buffer RadianceSums { uint radianceSums[]; };
layout(rgba16f, binding = IMAGE_VALUE_RADIANCE) uniform writeonly image3D oRadiance;
uniform float uRadianceMax;
#endif
#ifdef OCCUPANCY_FROM_GRID
layout(std430, binding = BINDING_PYRAMID) readonly buffer PyramidWords { uint pyramidWords[]; };
#endif
void main() {
  uvec3 cell = gl_GlobalInvocationID + uFirstCell;
  if (any(greaterThanEqual(cell, uEndCell))) return;
  uint i = valueIndex(cell, uResolution, 0u);
  uint n = counts[i / 4u];
  ivec3 c = ivec3(cell);
  imageStore(oCount, c, uvec4(n));
#ifdef OCCUPANCY_FROM_GRID
  bool occupied = (pyramidWords[columnWordIndex(cell.x, cell.y, depthWord(cell.z), uResolution)] & depthBit(cell.z)) != 0u;
  if (!occupied) n = 0u;
#else
  bool occupied = n > 0u;
#endif
  imageStore(oOccupancy, c, vec4(occupied ? 1.0f : 0.0f));
#ifdef VALUE_NORMAL
  imageStore(oNormal, c, n > 0u ? decodeValueMean(uvec4(normalSums[i], normalSums[i + 1u], normalSums[i + 2u], normalSums[i + 3u]), n, VALUE_CHANNEL_NORMAL) : vec4(0.0f));
#endif
#ifdef VALUE_ALBEDO
  imageStore(oAlbedo, c, n > 0u ? decodeValueMean(uvec4(albedoSums[i], albedoSums[i + 1u], albedoSums[i + 2u], albedoSums[i + 3u]), n, VALUE_CHANNEL_ALBEDO) : vec4(0.0f));
#endif
#ifdef VALUE_GLOSSY
  imageStore(oGlossy, c, n > 0u ? decodeValueMean(uvec4(glossySums[i], glossySums[i + 1u], glossySums[i + 2u], glossySums[i + 3u]), n, VALUE_CHANNEL_GLOSSY) : vec4(0.0f));
#endif
#ifdef VALUE_RADIANCE
  imageStore(oRadiance, c, premultipliedRadiance(uvec4(radianceSums[i], radianceSums[i + 1u], radianceSums[i + 2u], 0u), n, occupied, uRadianceMax));
#endif
}
