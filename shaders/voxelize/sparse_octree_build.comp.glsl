// The sparse voxel octree's build passes (voxelize/sparse_octree.h; OpenGL
// Insights ch. 22 §22.5: flag, allocate, initialise per level), one program per
// pass (define):
//   COUNT_FRAGMENTS  per 32-bit word of the binary grid (the OR-mip pyramid's
//                    level 0): its set bits added to the counter;
//   WRITE_FRAGMENTS  the same words' cells appended to the fragment list
//                    (packed, svoPackCell): one fragment per occupied cell, so
//                    the octree is built from any voxelizer of the registry;
//   FLAG             per fragment: descend to uLevel and flag the node (with
//                    DILATE the eight svoFlagTarget offsets); the node keeps
//                    its cell (BINDING_SVO_COORDS);
//   ALLOCATE         per node of level uLevel (uFirst …): a flagged one gets a
//                    tile of 8 children (atomic counter; the new tiles were
//                    cleared to SVO_NONE: the initialisation).
#include "shared/sparse_octree.glsl"
#include "shared/voxel_grid.glsl"
#include "shared/bindings.glsl"
layout(std430, binding = BINDING_VOXEL_COUNTER) buffer Counter { uint counter; };
#if defined(COUNT_FRAGMENTS) || defined(WRITE_FRAGMENTS)
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(std430, binding = BINDING_PYRAMID) readonly buffer PyramidWords { uint pyramidWords[]; };
uniform uvec4 uResolution;  // the grid's, w = D / 128
#ifdef WRITE_FRAGMENTS
layout(std430, binding = BINDING_SVO_FRAGMENTS) writeonly buffer Fragments { uint fragments[]; };
#endif
void main() {
  uvec3 g = gl_GlobalInvocationID;
  if (g.x >= uResolution.x || g.y >= uResolution.y || g.z >= uResolution.z / 32u) return;
  uint word = pyramidWords[columnWordIndex(g.x, g.y, g.z, uResolution)];
  if (word == 0u) return;
#ifdef COUNT_FRAGMENTS
  atomicAdd(counter, uint(bitCount(word)));
#else
  uint at = atomicAdd(counter, uint(bitCount(word)));
  for (uint b = 0u; b < 32u; ++b)
    if ((word & (1u << b)) != 0u) fragments[at++] = svoPackCell(uvec3(g.x, g.y, g.z * 32u + b));
#endif
}
#else
layout(local_size_x = 64) in;
layout(std430, binding = BINDING_SVO_NODES) buffer Nodes { uint svoNodes[]; };
layout(std430, binding = BINDING_SVO_COORDS) buffer Coords { uint svoCoords[]; };
uniform uint uLevel;
uniform uint uCount;  // invocations
uniform uint uFirst;  // ALLOCATE: the level's first node
uniform uint uDepth;
uint invocation() { return gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 64u + gl_GlobalInvocationID.x; }
#ifdef FLAG
layout(std430, binding = BINDING_SVO_FRAGMENTS) readonly buffer Fragments { uint fragments[]; };
// own: the fragment's own node (marked occupied), else a dilated one.
void flagCell(uvec3 cell, bool own) {
  uint n = 0u;
  for (uint l = 0u; l < uLevel; ++l) {
    uint child = svoChild(svoNodes[n]);
    if (child < SVO_TILE) return;  // not allocated: cannot happen for a flagged ancestor
    n = child + svoOctant(cell, uLevel - 1u - l);
  }
  atomicOr(svoNodes[n], own ? SVO_FLAGGED | SVO_OCCUPIED : SVO_FLAGGED);
  svoCoords[n] = svoPackCell(cell);
}
void main() {
  uint i = invocation();
  if (i >= uCount) return;
  uvec3 f = svoUnpackCell(fragments[i]);
#ifdef DILATE
  for (uint k = 0u; k < 8u; ++k) {
    if (svoDilationRepeats(f, uLevel, uDepth, svoOctantOffset(k))) continue;
    SvoTarget t = svoFlagTarget(f, uLevel, uDepth, svoOctantOffset(k));
    if (t.valid) flagCell(t.cell, k == 0u);
  }
#else
  flagCell(svoFlagTarget(f, uLevel, uDepth, uvec3(0u)).cell, true);
#endif
}
#endif
#ifdef ALLOCATE
void main() {
  uint i = invocation();
  if (i >= uCount) return;
  uint n = uFirst + i;
  uint word = svoNodes[n];
  if (svoChild(word) == SVO_FLAGGED) svoNodes[n] = (word & SVO_OCCUPIED) | atomicAdd(counter, 1u) * SVO_TILE;
}
#endif
#endif
