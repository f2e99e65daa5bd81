// The cells one atlas point inserts into, for both insertion shaders: its own
// cell, then (uFootprint > 0) every other cell of its footprint that its
// triangle overlaps (shaders/shared/atlas_footprint.glsl). The including shader
// defines `void visitCell(ivec2 texel, uvec3 cell)` first.
#include "grid_uniforms.glsl"
#include "shared/triangle_box.glsl"
#include "shared/atlas_footprint.glsl"
#include "shared/bindings.glsl"
layout(binding = TEXUNIT_ATLAS_POSITION) uniform sampler2D atlasPosition;
layout(binding = TEXUNIT_ATLAS_TRIANGLE) uniform isampler2D atlasTriangle;
layout(std430, binding = BINDING_ATLAS_CORNERS) readonly buffer Corners { float corners[]; };  // the mesh's VBO
uniform ivec2 uAtlasSize;
uniform float uFootprint;  // world radius; 0: the point only
uniform mat4 uModel;  // object → offset from the grid's origin (AtlasVoxelizer::modelToBox)
// The atlas's points → offsets from the grid's origin: a dynamic mesh's kept atlas holds object space
// (uPointModel = uModel: the points move with the mesh, no atlas is drawn per frame); a static mesh's
// atlas holds the offsets (identity, which changes no bit).
uniform mat4 uPointModel;
// A kept atlas's texels that hold a point (x | y << 16), listed once (AtlasVoxelizer::keepAtlas): with
// uListed > 0 the dispatch is one invocation per listed texel, 64 a workgroup, instead of one per texel
// of the atlas — the same points, without the invocations of the empty texels.
layout(std430, binding = BINDING_ATLAS_POINTS) readonly buffer AtlasPoints { uint atlasPoints[]; };
uniform int uListed;  // 0: the dispatch covers the atlas (8 × 8 texels a workgroup); > 0: that many listed

// The texel this invocation inserts; false past the atlas or the list.
bool insertionTexel(out ivec2 t) {
  if (uListed > 0) {
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u + gl_LocalInvocationIndex;
    if (i >= uint(uListed)) return false;
    uint v = atlasPoints[i];
    t = ivec2(int(v & 0xffffu), int(v >> 16));
    return true;
  }
  t = ivec2(gl_GlobalInvocationID.xy);
  return t.x < uAtlasSize.x && t.y < uAtlasSize.y;
}

vec3 gridCorner(GridParams g, int i) {
  int o = ATLAS_VERTEX_FLOATS * i;
  precise vec4 w = uModel * vec4(corners[o], corners[o + 1], corners[o + 2], 1.0f);  // rounds like the CPU
  return offsetToGrid(g, w.xyz);
}

// False if the texel holds no point.
bool visitPointCells(ivec2 t) {
  vec4 p = texelFetch(atlasPosition, t, 0);
  if (p.w == 0.0f) return false;
  GridParams g = gridFromUniforms();
  precise vec4 moved = uPointModel * vec4(p.xyz, 1.0f);  // rounds like the CPU (the points' read-back)
  vec3 q = offsetToGrid(g, moved.xyz);
  if (!insideGrid(g, q)) return true;
  uvec3 own = gridCell(g, q);
  visitCell(t, own);
  int tri = texelFetch(atlasTriangle, t, 0).x;
  if (uFootprint <= 0.0f || tri < 0) return true;
  vec3 a = gridCorner(g, 3 * tri), b = gridCorner(g, 3 * tri + 1), c = gridCorner(g, 3 * tri + 2);
  CellRange r = footprintCells(g, q, uFootprint);
  for (int z = r.lo.z; z <= r.hi.z; ++z)
    for (int y = r.lo.y; y <= r.hi.y; ++y)
      for (int x = r.lo.x; x <= r.hi.x; ++x) {
        uvec3 cell = uvec3(x, y, z);
        if (cell != own && triangleOverlapsBox(vec3(x, y, z) + 0.5f, vec3(0.5f), a, b, c)) visitCell(t, cell);
      }
  return true;
}
