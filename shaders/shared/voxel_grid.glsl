// Voxel grid conventions shared by the GL voxelizers/tracers and the CPU code
// (DESIGN.md): an oriented box (origin, three unit axes, extent) holding W×H×D
// cells. x, y address texels of the 2D column texture; z is the depth axis.
// D is a multiple of 128: one RGBA32UI slab per 128 depth cells; depth cell k
// lives in slab k/128, component (k%128)/32, bit k%32 — i.e. in the column's
// 32-bit word k/32 at bit k%32.
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
SHARED_BEGIN

struct GridParams {
  vec4 origin;      // xyz: corner of cell (0,0,0)
  vec4 axisX;       // xyz: unit axis, w: cells per world unit along it (W / extent.x)
  vec4 axisY;       // likewise for H
  vec4 axisZ;       // likewise for D
  uvec4 resolution; // W, H, D, D/128 (slabs)
};

// An offset from the box's corner (world position − origin) → continuous grid
// coordinates (cell (i,j,k) spans [i, i+1) × …). Positions kept as offsets keep
// their precision far from the world's origin, where a float's step can be a
// large part of a cell (the atlas voxelizer stores its points so).
// precise: the GPU must round like the CPU (GLSL would fuse the dot products).
SHARED_FN vec3 offsetToGrid(SHARED_IN(GridParams) g, vec3 d) {
  SHARED_PRECISE vec3 q = vec3(dot(d, vec3(g.axisX.x, g.axisX.y, g.axisX.z)) * g.axisX.w,
                               dot(d, vec3(g.axisY.x, g.axisY.y, g.axisY.z)) * g.axisY.w,
                               dot(d, vec3(g.axisZ.x, g.axisZ.y, g.axisZ.z)) * g.axisZ.w);
  return q;
}

// World position → continuous grid coordinates.
SHARED_FN vec3 worldToGrid(SHARED_IN(GridParams) g, vec3 p) {
  SHARED_PRECISE vec3 d = p - vec3(g.origin.x, g.origin.y, g.origin.z);
  return offsetToGrid(g, d);
}

// Continuous grid coordinates → world position (the inverse of worldToGrid).
SHARED_FN vec3 gridToWorld(SHARED_IN(GridParams) g, vec3 q) {
  return vec3(g.origin.x, g.origin.y, g.origin.z) + vec3(g.axisX.x, g.axisX.y, g.axisX.z) * (q.x / g.axisX.w) +
         vec3(g.axisY.x, g.axisY.y, g.axisY.z) * (q.y / g.axisY.w) +
         vec3(g.axisZ.x, g.axisZ.y, g.axisZ.z) * (q.z / g.axisZ.w);
}

// The cell holding grid position q; positions exactly on the upper boundary
// belong to the last cell (the box is closed). Callers check insideGrid first.
SHARED_FN uvec3 gridCell(GridParams g, vec3 q) {
  return uvec3(min(uint(max(q.x, 0.0f)), g.resolution.x - 1u), min(uint(max(q.y, 0.0f)), g.resolution.y - 1u),
               min(uint(max(q.z, 0.0f)), g.resolution.z - 1u));
}

SHARED_FN bool insideGrid(GridParams g, vec3 q) {
  return q.x >= 0.0f && q.y >= 0.0f && q.z >= 0.0f && q.x <= float(g.resolution.x) &&
         q.y <= float(g.resolution.y) && q.z <= float(g.resolution.z);
}

// Word of the column (0 … D/32−1) and the bit in it for depth cell k.
SHARED_FN uint depthWord(uint k) { return k >> 5u; }
SHARED_FN uint depthBit(uint k) { return 1u << (k & 31u); }

// Bits first…last (inclusive, 0 ≤ first ≤ last ≤ 31) of one word. Never shifts
// by 32 (undefined in C++ and GLSL): both shifts stay in 0…31.
SHARED_FN uint bitRange(uint first, uint last) {
  return (0xffffffffu >> (31u - last)) & (0xffffffffu << first);
}

// Index of word w of column (x, y) in the flat word array: slab-major, then
// rows, columns, and the four components — the layout of a GL_TEXTURE_2D_ARRAY
// RGBA32UI with one layer per slab, and of the SSBO the GL voxelizers fill.
SHARED_FN uint columnWordIndex(uint x, uint y, uint w, uvec4 resolution) {
  return (((w >> 2u) * resolution.y + y) * resolution.x + x) * 4u + (w & 3u);
}

// One atlas point: the word to OR and the bit, or word = 0xffffffff outside the grid.
struct PointBit {
  uint word;
  uint bit;
};

SHARED_FN PointBit pointBit(GridParams g, vec3 offset) {  // offset: world position − origin
  PointBit r;
  vec3 q = offsetToGrid(g, offset);
  if (!insideGrid(g, q)) {
    r.word = 0xffffffffu;
    r.bit = 0u;
    return r;
  }
  uvec3 c = gridCell(g, q);
  r.word = columnWordIndex(c.x, c.y, depthWord(c.z), g.resolution);
  r.bit = depthBit(c.z);
  return r;
}

SHARED_END
