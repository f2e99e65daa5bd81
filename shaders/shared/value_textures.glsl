// GLSL lookups of the multi-valued grids' 3D textures (voxelize/value_textures.h).
// The coordinate and weight maths is shared with C++ (value_grid.glsl:
// valueUvw, anisoFaces, anisoWeights); the texture reads are GLSL only.
// Bind with ValueTextures::bind() (and bindAniso(channel) for the six faces).
#include "value_grid.glsl"
#include "bindings.glsl"
layout(binding = TEXUNIT_VALUE_OCCUPANCY) uniform sampler3D valueOccupancy;
layout(binding = TEXUNIT_VALUE_NORMAL) uniform sampler3D valueNormal;
layout(binding = TEXUNIT_VALUE_ALBEDO) uniform sampler3D valueAlbedo;
layout(binding = TEXUNIT_VALUE_GLOSSY) uniform sampler3D valueGlossy;
layout(binding = TEXUNIT_VALUE_COUNT) uniform usampler3D valueCount;
layout(binding = TEXUNIT_VALUE_RADIANCE) uniform sampler3D valueRadiance;  // premultiplied: w = occupancy
layout(binding = TEXUNIT_VALUE_ANISO) uniform sampler3D valueAniso0;  // +x
layout(binding = TEXUNIT_VALUE_ANISO + 1) uniform sampler3D valueAniso1;  // −x
layout(binding = TEXUNIT_VALUE_ANISO + 2) uniform sampler3D valueAniso2;  // +y
layout(binding = TEXUNIT_VALUE_ANISO + 3) uniform sampler3D valueAniso3;  // −y
layout(binding = TEXUNIT_VALUE_ANISO + 4) uniform sampler3D valueAniso4;  // +z
layout(binding = TEXUNIT_VALUE_ANISO + 5) uniform sampler3D valueAniso5;  // −z

// The occupancy-weighted mean of a channel (valueNormal, valueAlbedo,
// valueGlossy) around uvw at mip level `lod` (trilinear; 0 where no cell it
// blends has points).
vec4 valueMean(sampler3D channel, vec3 uvw, float lod) {
  float occ = textureLod(valueOccupancy, uvw, lod).x;
  return occ > 0.0f ? textureLod(channel, uvw, lod) / occ : vec4(0.0f);
}

// Face f of the bound anisotropic chain at the grid's level lod ≥ 1 (the
// faces' own level lod − 1). A switch: sampler arrays may only be indexed
// with dynamically uniform values.
vec4 valueAnisoFace(uint f, vec3 uvw, float lod) {
  float l = lod - 1.0f;
  switch (f) {
    case 0u: return textureLod(valueAniso0, uvw, l);
    case 1u: return textureLod(valueAniso1, uvw, l);
    case 2u: return textureLod(valueAniso2, uvw, l);
    case 3u: return textureLod(valueAniso3, uvw, l);
    case 4u: return textureLod(valueAniso4, uvw, l);
    default: return textureLod(valueAniso5, uvw, l);
  }
}

// The anisotropic chain seen along unit direction d (premultiplied rgb, alpha
// = occupancy composed front to back), at the grid's level lod ≥ 1, the three
// faces weighted by w (anisoWeights(d): d², summing to 1; or |d|, Dinse 2015).
vec4 valueAniso(vec3 uvw, vec3 d, float lod, vec3 w) {
  uvec3 f = anisoFaces(d);
  return w.x * valueAnisoFace(f.x, uvw, lod) + w.y * valueAnisoFace(f.y, uvw, lod) +
         w.z * valueAnisoFace(f.z, uvw, lod);
}
