// Binary atlas voxelization, insertion (VGI §3.1): one point per valid atlas
// texel sets the bit of its cell with atomicOr, through the shared kernel
// (pointBit) that the CPU build runs too.
#include "grid_uniforms.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D atlasPosition;
layout(std430, binding = 0) buffer Columns { uint words[]; };
layout(std430, binding = 1) buffer Counters { uint points; };
uniform ivec2 uAtlasSize;
void main() {
  ivec2 t = ivec2(gl_GlobalInvocationID.xy);
  if (t.x >= uAtlasSize.x || t.y >= uAtlasSize.y) return;
  vec4 p = texelFetch(atlasPosition, t, 0);
  if (p.w == 0.0f) return;
  atomicAdd(points, 1u);
  PointBit b = pointBit(gridFromUniforms(), p.xyz);
  if (b.word != 0xffffffffu) atomicOr(words[b.word], b.bit);
}
