// The binary grid's side of an atlas insertion: the cell's bit set with atomicOr
// in the word SSBO, and the points counted (atlas_insert.comp.glsl; the value
// insertion does the same in its pass under INSERT_BITS).
#include "shared/bindings.glsl"
layout(std430, binding = BINDING_GRID_WORDS) buffer Columns { uint words[]; };
layout(std430, binding = BINDING_VOXEL_COUNTER) buffer Counters { uint points; };
void setCellBit(uvec3 c) { atomicOr(words[columnWordIndex(c.x, c.y, depthWord(c.z), uResolution)], depthBit(c.z)); }
