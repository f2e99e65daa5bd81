// The gather kit's visibility between neighbours (GATHER_VISIBILITY, the kit's `blur_visibility`;
// illum/kits/gather_kit.h), included after gather.glsl by the kit's own passes — blur, upsampling,
// edges — which are then the only ones of their programs to include the tracer (the shader library
// includes a file once, also where an #ifdef drops it).
//
// Coplanar surfaces on the two sides of a thin wall (two rooms' floors, back walls) pass every
// geometry weight, and averaging them carries one room's light into the other. Two surfaces see each
// other where the method's voxels (its tracer, traverse/tracer.glsl) leave the segment between them
// free, both lifted off their surfaces (gatherLifted, gatherVisible). The edges pass (edges.comp.glsl)
// tests each gather pixel against its right and upper neighbours once per sample, into a mask of two
// bits; the blur counts a neighbour only if a path of open edges leads to it (along x then y, or y then
// x), so a wall closes the window behind it at two traces per gather pixel instead of one per
// neighbour; the upsampling counts the gather pixels of its 2×2 that the mask connects to the one
// nearest its pixel (no trace of its own).
#ifdef GATHER_VISIBILITY
#include "traverse/tracer.glsl"
// A surface point lifted off its voxels for a visibility test: the offset along its normal (off its
// own voxels, also where the eye sees it at a grazing angle) and the offset towards the eye. Along the
// normal alone, a point in a crease (a floor beside a wall) stays inside the wall's voxels; the eye
// sees the point, so the way towards it leaves them.
vec3 gatherLifted(vec3 p, vec3 n) {
  return p + (n + normalize(gather.camera.xyz - p)) * gather.visibilityOffset;
}
bool gatherVisible(vec3 p, vec3 n, vec3 pj, vec3 nj) { return visibleBetween(gatherLifted(p, n), gatherLifted(pj, nj)); }
const int kMaxInterleave = 8;  // the interleave parameter's maximum (illum/kits/gather_kit.cpp)
bool inGather(ivec2 a, ivec2 size) { return all(greaterThanEqual(a, ivec2(0))) && all(lessThan(a, size)); }
#ifndef GATHER_EDGES_PASS
layout(binding = TEXUNIT_PASS_INPUT2) uniform usampler2D uGatherEdges;
// Bit 0: gather pixel a and a + (1, 0) see each other; bit 1: a and a + (0, 1).
bool gatherEdgeOpen(ivec2 a, int axis) { return ((texelFetch(uGatherEdges, a, 0).x >> uint(axis)) & 1u) != 0u; }
#endif
#endif
