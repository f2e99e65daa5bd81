// The sparse voxel octree's values (voxelize/sparse_octree.h): the leaves'
// resolve, the mip filtering up the tree, and the bricks' borders, one
// program per pass (define), over one level's nodes (uFirst, uCount):
//   RESOLVE  per leaf node: its premultiplied radiance (L·α, α) from the
//            injection's sums (slot = node − uFirst), the dense volume's own
//            function (premultipliedRadiance), into the iso pool; RADIANCE_NONE:
//            opacity only (α of the occupied leaves);
//   FILTER   per node with children: the reduction of its brick's 2×2×2
//            children (uInput) — boxMean8, or under ANISOTROPIC face uFace's
//            anisoReduce, the dense chain's kernels — written into its own
//            tile's brick at its octant (the root: texel (1,1,1) of brick 0);
//   BORDERS  per node with children: its tile's brick's +x/+y/+z border
//            texels from the neighbouring tiles' children (0 where the
//            neighbour has none), read and written in the same pool image —
//            in all POOLS pools of one layout at once (the six faces, or the
//            iso pool), so the neighbours are found once.
// Brick b of a pool is tile t − base (uInBase, uOutBase).
#include "shared/sparse_octree_lookup.glsl"
#include "shared/value_grid.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = BINDING_SVO_COORDS) readonly buffer Coords { uint svoCoords[]; };
uniform uint uFirst;
uniform uint uCount;
uniform uint uLevel;
uniform uvec3 uInBricks;   // the input pool's bricks per axis
uniform uvec3 uOutBricks;  // the output pool's
uniform uint uInBase;
uniform uint uOutBase;
// This invocation's node of the level, or SVO_NO_SLOT past its end.
uint levelNode() {
  uint i = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 64u + gl_GlobalInvocationID.x;
  return i < uCount ? uFirst + i : SVO_NO_SLOT;
}

#if defined(RESOLVE) || defined(FILTER)
layout(rgba16f, binding = IMAGE_OUTPUT) uniform writeonly image3D oPool;
// Writes node n's value into its tile's brick (the root: brick 0, texel (1,1,1)).
void storeNode(uint n, vec4 v) {
  uvec3 texel = n == 0u ? uvec3(1u) : svoBrickOrigin((n >> 3u) - uOutBase, uOutBricks) + svoOctantOffset(n & 7u);
  imageStore(oPool, ivec3(texel), v);
}
#endif

#ifdef RESOLVE
layout(std430, binding = BINDING_VALUE_COUNTS) readonly buffer Counts { uint counts[]; };
layout(std430, binding = BINDING_VALUE_RADIANCE) readonly buffer RadianceSums { uint radianceSums[]; };
uniform float uRadianceMax;
void main() {
  uint n = levelNode();
  if (n == SVO_NO_SLOT) return;
  uint i = n - uFirst;  // the leaf's slot
  bool occupied = svoOccupied(svoNodes[n]);
#ifdef RADIANCE_NONE
  storeNode(n, occupied ? vec4(0.0f, 0.0f, 0.0f, 1.0f) : vec4(0.0f));
#else
  uvec4 sums = uvec4(radianceSums[4u * i], radianceSums[4u * i + 1u], radianceSums[4u * i + 2u], 0u);
  storeNode(n, premultipliedRadiance(sums, counts[i], occupied, uRadianceMax));
#endif
}
#endif

#ifdef FILTER
layout(binding = TEXUNIT_PASS_INPUT) uniform sampler3D uInput;
uniform uint uFace;
void main() {
  uint n = levelNode();
  if (n == SVO_NO_SLOT) return;
  uint child = svoChild(svoNodes[n]);
  if (child < SVO_TILE) return;  // no children: the cleared 0 stands
  ivec3 origin = ivec3(svoBrickOrigin((child >> 3u) - uInBase, uInBricks));
  vec4 c[8];
  for (uint k = 0u; k < 8u; ++k) c[k] = texelFetch(uInput, origin + ivec3(svoOctantOffset(k)), 0);
#ifdef ANISOTROPIC
  storeNode(n, anisoReduce(c, uFace));
#else
  storeNode(n, boxMean8(c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]));
#endif
}
#endif

#ifdef BORDERS
layout(rgba16f, binding = IMAGE_OUTPUT) uniform image3D oPools[POOLS];
void main() {
  uint n = levelNode();
  if (n == SVO_NO_SLOT) return;
  uint child = svoChild(svoNodes[n]);
  if (child < SVO_TILE) return;
  uvec3 cell = svoUnpackCell(svoCoords[n]);
  ivec3 origin = ivec3(svoBrickOrigin((child >> 3u) - uOutBase, uOutBricks));
  uint side = 1u << uLevel;
  // The (up to 7) neighbouring nodes on the +side, each read once.
  for (uint k = 1u; k < 8u; ++k) {
    uvec3 o = svoOctantOffset(k);
    uvec3 nb = cell + o;
    uint m = (nb.x < side && nb.y < side && nb.z < side) ? svoFind(nb, uLevel) : SVO_NO_SLOT;
    uint nbChild = m == SVO_NO_SLOT ? SVO_NONE : svoChild(svoNodes[m]);
    ivec3 from = nbChild < SVO_TILE ? ivec3(0) : ivec3(svoBrickOrigin((nbChild >> 3u) - uOutBase, uOutBricks));
    // The border texels b (some component 2) whose neighbour is o: b = 2 exactly where o = 1.
    for (uint j = 0u; j < 8u; ++j) {
      uvec3 lo = svoOctantOffset(j);  // the texel within the neighbour's children
      bool inside = true;
      for (int a = 0; a < 3; ++a) if (o[a] == 1u && lo[a] != 0u) inside = false;
      if (!inside) continue;
      uvec3 b = uvec3(o.x == 1u ? 2u : lo.x, o.y == 1u ? 2u : lo.y, o.z == 1u ? 2u : lo.z);
      for (int p = 0; p < POOLS; ++p)
        imageStore(oPools[p], origin + ivec3(b), nbChild < SVO_TILE ? vec4(0.0f) : imageLoad(oPools[p], from + ivec3(lo)));
    }
  }
}
#endif
