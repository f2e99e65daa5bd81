// Multi-valued atlas voxelization, insertion: one point per valid atlas texel
// adds its values (shaders/shared/value_grid.glsl) to its cell and, with a
// footprint, to the other cells it sets in the binary grid
// (atlas_point_cells.glsl), so every set cell has values. Only the channels a
// caller asked for are compiled in (VALUE_NORMAL, VALUE_ALBEDO, VALUE_GLOSSY;
// VALUE_RADIANCE alone in the radiance pass, which leaves the counts to the
// pass that inserted the same points). With INSERT_BITS the same pass sets the
// binary grid's bits and counts the points too (atlas_insert_bits.glsl): one walk
// over the points and their footprints instead of two.
#include "grid_uniforms.glsl"
#include "shared/value_grid.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
#include "shared/bindings.glsl"
layout(binding = TEXUNIT_ATLAS_NORMAL) uniform sampler2D atlasNormal;
layout(binding = TEXUNIT_ATLAS_ALBEDO) uniform sampler2D atlasAlbedo;
layout(binding = TEXUNIT_ATLAS_GLOSSY) uniform sampler2D atlasGlossy;
layout(std430, binding = BINDING_VALUE_COUNTS) buffer Counts { uint counts[]; };
layout(std430, binding = BINDING_VALUE_NORMAL) buffer NormalSums { uint normalSums[]; };
layout(std430, binding = BINDING_VALUE_ALBEDO) buffer AlbedoSums { uint albedoSums[]; };
layout(std430, binding = BINDING_VALUE_GLOSSY) buffer GlossySums { uint glossySums[]; };
uniform mat4 uNormalModel;  // a kept (object-space) atlas's normals → the grid's (normal matrix)
uniform int uTurnNormals;   // 1: the atlas is kept (a dynamic mesh); 0: its normals are the grid's already
#ifdef VALUE_RADIANCE
layout(binding = TEXUNIT_ATLAS_RADIANCE) uniform sampler2D atlasRadiance;
layout(std430, binding = BINDING_VALUE_RADIANCE) buffer RadianceSums { uint radianceSums[]; };
uniform float uRadianceMax;
#endif
#ifdef INSERT_BITS
#include "atlas_insert_bits.glsl"
#endif
void visitCell(ivec2 t, uvec3 cell) {
#ifdef INSERT_BITS
  setCellBit(cell);
#endif
#ifdef VALUE_RADIANCE
  vec4 r = texelFetch(atlasRadiance, t, 0);
  for (uint c = 0u; c < 3u; ++c) atomicAdd(radianceSums[valueIndex(cell, uResolution, c)], toFixedRadiance(r[c], uRadianceMax));
#else
  atomicAdd(counts[valueIndex(cell, uResolution, 0u) / 4u], 1u);
#endif
#ifdef VALUE_NORMAL
  vec4 n = texelFetch(atlasNormal, t, 0);
  if (uTurnNormals != 0 && dot(n.xyz, n.xyz) > 0.0f) n.xyz = normalize(mat3(uNormalModel) * n.xyz);
  for (uint c = 0u; c < 3u; ++c) atomicAdd(normalSums[valueIndex(cell, uResolution, c)], toFixed(n[c], -1.0f, 1.0f));
#endif
#ifdef VALUE_ALBEDO
  vec4 a = texelFetch(atlasAlbedo, t, 0);
  for (uint c = 0u; c < 3u; ++c) atomicAdd(albedoSums[valueIndex(cell, uResolution, c)], toFixed(a[c], 0.0f, 1.0f));
#endif
#ifdef VALUE_GLOSSY
  vec4 s = texelFetch(atlasGlossy, t, 0);
  for (uint c = 0u; c < 3u; ++c) atomicAdd(glossySums[valueIndex(cell, uResolution, c)], toFixed(s[c], 0.0f, 1.0f));
  atomicAdd(glossySums[valueIndex(cell, uResolution, 3u)], toFixed(encodeExponent(s.w), 0.0f, exponentCodeMax()));
#endif
}
#include "atlas_point_cells.glsl"
void main() {
  ivec2 t;
  if (!insertionTexel(t)) return;
#ifdef INSERT_BITS
  if (visitPointCells(t)) atomicAdd(points, 1u);
#else
  visitPointCells(t);
#endif
}
