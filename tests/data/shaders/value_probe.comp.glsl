// Test probe (tests/voxelize/value_textures_test.cpp): the value-texture
// lookups of shaders/shared/value_textures.glsl at given world points.
#include "../../../shaders/shared/value_textures.glsl"
#include "../../../shaders/voxelize/grid_uniforms.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = BINDING_TRACE_RAYS) readonly buffer Points { vec4 points[]; };  // xyz world, w lod
layout(std430, binding = BINDING_TRACE_HITS) writeonly buffer Results { vec4 results[]; };  // 4 per point
uniform vec3 uDirection;
uniform int uCount;
void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= uCount) return;
  vec3 uvw = valueUvw(gridFromUniforms(), points[i].xyz);
  float lod = points[i].w;
  results[4 * i] = vec4(textureLod(valueOccupancy, uvw, lod).x, float(texture(valueCount, uvw).x), 0.0f, 0.0f);
  results[4 * i + 1] = textureLod(valueNormal, uvw, lod);
  results[4 * i + 2] = valueMean(valueAlbedo, uvw, lod);
  results[4 * i + 3] = lod >= 1.0f ? valueAniso(uvw, uDirection, lod, anisoWeights(uDirection)) : vec4(0.0f);
}
