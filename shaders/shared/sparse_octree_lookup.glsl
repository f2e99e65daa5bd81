// GLSL lookups in the sparse voxel octree (voxelize/sparse_octree.h; the
// layout in sparse_octree.glsl): the node holding a cell, a leaf's slot, and the
// trilinear sample of a level through its brick. Bound by
// SparseVoxelOctree::bind (the node pool, the uniforms; the pools at the dense
// volume's units: the iso pool at TEXUNIT_VALUE_RADIANCE, the six face pools
// at TEXUNIT_VALUE_ANISO + f).
#include "sparse_octree.glsl"
#include "bindings.glsl"
layout(std430, binding = BINDING_SVO_NODES) readonly buffer SvoNodes { uint svoNodes[]; };
uniform uint uSvoDepth;      // D: the leaves' level (2^D cells per axis)
uniform uint uSvoLeafFirst;  // the first leaf node: a leaf's slot is node − this
uniform uvec3 uSvoIsoBricks;   // bricks per axis of the iso pool
uniform uvec3 uSvoFaceBricks;  // … of the face pools
uniform uint uSvoIsoBase;      // the iso pool's brick of tile t is t − this

// The node at `level` holding `cell` (level-`level` cells), or SVO_NO_SLOT
// where the tree ends above it.
uint svoFind(uvec3 cell, uint level) {
  uint n = 0u;
  for (uint l = 0u; l < level; ++l) {
    uint child = svoChild(svoNodes[n]);
    if (child < SVO_TILE) return SVO_NO_SLOT;
    n = child + svoOctant(cell, level - 1u - l);
  }
  return n;
}

// The slot of leaf cell c (its sums), or SVO_NO_SLOT where it is not in the tree.
uint svoLeafSlot(uvec3 c) {
  uint n = svoFind(c, uSvoDepth);
  return n == SVO_NO_SLOT ? SVO_NO_SLOT : n - uSvoLeafFirst;
}

// The brick that holds the trilinear stencil of level m around grid point q
// (leaf cells), and q's texel coordinates u within it; false where none does.
// Within half a cell of the grid's low faces the stencil's lower cells lie
// outside (0, as the dense texture's border): u sits on the inner cells'
// centre along that axis and `scale` is the inner cells' trilinear weight
// (the blend is separable), so the sample equals the dense one there too.
struct SvoStencil {
  uint tile;
  vec3 u;
  float scale;
  bool found;
};
SvoStencil svoStencil(vec3 q, uint m) {
  SvoStencil s;
  vec3 p = q * exp2(float(m) - float(uSvoDepth));
  s.found = true;
  s.scale = 1.0f;
  if (m == 0u) {
    s.tile = 0u;
    s.u = p + 1.0f;  // the root at texel (1,1,1)
    return s;
  }
  ivec3 lo = ivec3(floor(p - 0.5f));
  int side = 1 << int(m);
  s.found = all(greaterThanEqual(lo, ivec3(-1))) && all(lessThan(lo, ivec3(side)));
  if (!s.found) return s;
  uvec3 parent = uvec3(max(lo, ivec3(0))) >> 1u;
  uint n = svoFind(parent, m - 1u);
  uint child = n == SVO_NO_SLOT ? SVO_NONE : svoChild(svoNodes[n]);
  s.found = child >= SVO_TILE;
  s.tile = child >> 3u;
  s.u = p - 2.0f * vec3(parent);
  for (int a = 0; a < 3; ++a)
    if (lo[a] < 0) {
      s.scale *= p[a] + 0.5f;
      s.u[a] = 0.5f;
    }
  return s;
}

// The pool texel coordinates of u in brick b.
vec3 svoPoolUvw(uint b, uvec3 bricks, vec3 u) {
  return (vec3(svoBrickOrigin(b, bricks)) + u) / vec3(bricks * SVO_BRICK);
}
