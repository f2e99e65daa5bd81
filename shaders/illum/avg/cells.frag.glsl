// The AVG's construction, per fragment of the three-axis conservative
// rasterization (voxelize/conservative.geom + conservative_cells.glsl): every
// cell the triangle overlaps adds the triangle's unit normal, its albedo
// (the material's, times its texture at the triangle's centroid uv — the
// paper's lowest mip level stands for the same: one colour per triangle and
// cell) and 1 to the cell's sums (shared/avg.glsl).
#include "shared/constants.glsl"
#include "shared/sampling.glsl"
#include "shared/brdf.glsl"
#include "shared/environment.glsl"
#include "shared/gpu_scene.glsl"
#include "shared/avg.glsl"
#include "voxelize/conservative_cells.glsl"
layout(std430, binding = BINDING_AVG) buffer AvgCells { uint avgCells[]; };
flat in vec3 gWorldNormal;
flat in vec2 gUvCentroid;

void visitCell(uvec3 c) {
  int m = triMaterial[gl_PrimitiveID];
  vec3 albedo = materials[m].albedoLayer.xyz;
  float layer = materials[m].albedoLayer.w;
  if (layer >= 0.0f) albedo *= texture(albedoTextures, vec3(gUvCentroid.x, 1.0f - gUvCentroid.y, layer)).xyz;
  uint base = avgCellBase(c, uResolution.xyz);
  ivec3 n = ivec3(round(gWorldNormal * avgFixedScale()));
  uvec3 a = uvec3(round(clamp(albedo, 0.0f, 1.0f) * avgFixedScale()));
  atomicAdd(avgCells[base + 0u], uint(n.x));
  atomicAdd(avgCells[base + 1u], uint(n.y));
  atomicAdd(avgCells[base + 2u], uint(n.z));
  atomicAdd(avgCells[base + 3u], a.x);
  atomicAdd(avgCells[base + 4u], a.y);
  atomicAdd(avgCells[base + 5u], a.z);
  atomicAdd(avgCells[base + 6u], 1u);
}

void main() { visitTriangleCells(); }
