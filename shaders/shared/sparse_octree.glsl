// The sparse voxel octree of voxel cone tracing (Crassin & Green, "Octree-Based
// Sparse Voxelization Using the GPU Hardware Rasterizer", OpenGL Insights ch. 22,
// 2012; Crassin et al. 2011 §3; ../shared/papers/002_…, the 2013 article), as
// voxelize/sparse_octree.h builds it: the addressing that the GLSL build,
// filter and cone passes and the C++ reference share. Its files are named
// sparse_octree* everywhere (here, voxelize/, illum/resources/, the tests); its
// GLSL and C++ identifiers carry the short prefix svo / SVO_ (sparse voxel
// octree), as does the parameter value that selects it (vct volume=svo).
//
// Nodes: one uint each in a node pool, in tiles of 8 siblings (tile t = nodes
// 8t … 8t+7, octant x + 2y + 4z); node 0 is the root (tile 0 holds only it).
// A node's word (svoChild of it) is its children's first node (≥ 8), or
// SVO_NONE (no children: an empty node, or an empty leaf), or SVO_FLAGGED
// (while building: to be subdivided; at the leaf level, the depth D: an
// occupied leaf); its bit SVO_OCCUPIED says that fragments fall in it (a
// node allocated only by `dilate` lacks it: empty, though it has children).
// Levels are allocated one after another, so the nodes of a level are one range.
//
// Bricks: the values of the 8 children of a node (its tile) are one brick of
// 3×3×3 texels in a brick pool 3D texture: texels 0…1 along each axis are the
// children (octant offsets), texel 2 the neighbouring tile's first children
// on the +x/+y/+z side (the border). A trilinear sample at level m around grid
// point q blends the 2×2×2 level-m cells from c = floor(p − ½) (p = q in
// level-m cells); the brick of c's parent holds all eight, so one lookup and
// one hardware trilinear fetch give what the dense volume's texture gives —
// when that parent exists. Where it does not (an empty node whose +side
// neighbour has data) the sample misses the neighbour's share: the filled /
// empty brick-border artefact of VCT-AO §6.2. `dilate` allocates those
// parents too (svoFlagTarget with δ ∈ {0,1}³), which removes it.
// The root's value (level 0) sits at texel (1,1,1) of brick 0.
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
SHARED_BEGIN

const uint SVO_NONE = 0u;
const uint SVO_FLAGGED = 1u;
const uint SVO_TILE = 8u;         // nodes per tile
const uint SVO_BRICK = 3u;        // texels per brick side
const uint SVO_MAX_DEPTH = 10u;   // cells packed in 10 bits per axis (1024³)
const uint SVO_NO_SLOT = 0xffffffffu;
const uint SVO_OCCUPIED = 0x80000000u;
const uint SVO_CHILD_MASK = 0x7fffffffu;

SHARED_FN uint svoChild(uint word) { return word & SVO_CHILD_MASK; }
SHARED_FN bool svoOccupied(uint word) { return (word & SVO_OCCUPIED) != 0u; }

SHARED_FN uint svoPackCell(uvec3 c) { return c.x | (c.y << 10u) | (c.z << 20u); }
SHARED_FN uvec3 svoUnpackCell(uint p) { return uvec3(p & 1023u, (p >> 10u) & 1023u, (p >> 20u) & 1023u); }

// The octant (x + 2y + 4z) of a cell's bit `shift`: the child of the node
// above, for the cell's coordinates at a deeper level `shift` levels down.
SHARED_FN uint svoOctant(uvec3 cell, uint shift) {
  return ((cell.x >> shift) & 1u) | (((cell.y >> shift) & 1u) << 1u) | (((cell.z >> shift) & 1u) << 2u);
}
SHARED_FN uvec3 svoOctantOffset(uint o) { return uvec3(o & 1u, (o >> 1u) & 1u, (o >> 2u) & 1u); }

// The first texel of brick b in a pool of `bricks` bricks per axis.
SHARED_FN uvec3 svoBrickOrigin(uint b, uvec3 bricks) {
  uvec3 p = uvec3(b % bricks.x, (b / bricks.x) % bricks.y, b / (bricks.x * bricks.y));
  return p * SVO_BRICK;
}

// The node at `level` that fragment cell f (at the depth D) flags, with
// the dilation offset delta ∈ {0,1}³ (0: the fragment's own node): the parent
// of the fragment's level-(level + 1) cell minus delta, so every stencil that
// blends the fragment's cell finds its brick. At the leaf level the fragment
// itself. valid = false where the offset leaves the grid.
struct SvoTarget {
  uvec3 cell;
  bool valid;
};
SHARED_FN SvoTarget svoFlagTarget(uvec3 f, uint level, uint depth, uvec3 delta) {
  SvoTarget t;
  t.valid = true;
  if (level >= depth) {
    t.cell = f;
    t.valid = delta.x == 0u && delta.y == 0u && delta.z == 0u;
    return t;
  }
  uint s = depth - level - 1u;
  uvec3 a = uvec3(f.x >> s, f.y >> s, f.z >> s);
  t.valid = a.x >= delta.x && a.y >= delta.y && a.z >= delta.z;
  uvec3 b = a - delta;
  t.cell = uvec3(b.x >> 1u, b.y >> 1u, b.z >> 1u);
  return t;
}

// Whether offset delta flags the same node as a smaller offset (along an
// axis where the fragment's level-(level + 1) cell is odd, a − 1 and a have
// one parent): the flag pass skips it, about 2.4× fewer descents.
SHARED_FN bool svoDilationRepeats(uvec3 f, uint level, uint depth, uvec3 delta) {
  if (level >= depth) return false;
  uint s = depth - level - 1u;
  return (delta.x == 1u && ((f.x >> s) & 1u) == 1u) || (delta.y == 1u && ((f.y >> s) & 1u) == 1u) ||
         (delta.z == 1u && ((f.z >> s) & 1u) == 1u);
}

SHARED_END
