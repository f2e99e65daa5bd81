// Mip levels of the multi-valued grids' 3D textures (voxelize/value_textures.h),
// one dispatch per level and texture, through the shared kernels of
// shared/value_grid.glsl (what the C++ builder runs too):
//   ISOTROPIC     level L from L−1 of the same texture: boxMean8 of the children.
//   ANISOTROPIC   face uFace of a six-direction chain: anisoReduce of the
//                 children. Its level 0 (the grid's level 1) reads the
//                 channel's level-0 texture (rgb) with the occupancy as alpha
//                 (uFromValues = 1); later levels read the face's own level L−1.
//   DIRECTIONAL   (with ANISOTROPIC) that first level sees each cell's radiance
//                 from the side the face's cones come from: times
//                 directionalFacing(−travel, D), D the cell's direction of
//                 leaving light (vct's `directional`, illum/vct/direction_resolve.comp).
#include "shared/value_grid.glsl"
#include "shared/bindings.glsl"
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(binding = TEXUNIT_PASS_INPUT) uniform sampler3D uInput;
layout(binding = TEXUNIT_PASS_INPUT2) uniform sampler3D uOccupancy;
layout(OUTPUT_FORMAT, binding = IMAGE_OUTPUT) uniform writeonly image3D oLevel;
#ifdef DIRECTIONAL
layout(binding = TEXUNIT_VALUE_DIRECTION) uniform sampler3D uDirection;
#endif
uniform int uInputLevel;
uniform int uFromValues;
uniform uvec3 uFirstCell;  // the texels built: uFirstCell … uEndCell − 1 (all, or a changed box's parents)
uniform uvec3 uEndCell;
uniform uint uFace;
vec4 child(ivec3 p) {
  // An odd-sized level's last texel has children beyond its input: empty.
  if (any(greaterThanEqual(p, textureSize(uInput, uInputLevel)))) return vec4(0.0f);
  vec4 v = texelFetch(uInput, p, uInputLevel);
#ifdef ANISOTROPIC
  if (uFromValues != 0) {
#ifdef DIRECTIONAL
    v.xyz *= directionalFacing(-anisoFaceTravel(uFace), texelFetch(uDirection, p, 0).xyz);
#endif
    v = vec4(v.xyz, texelFetch(uOccupancy, p, 0).x);
  }
#endif
  return v;
}
void main() {
  ivec3 cell = ivec3(gl_GlobalInvocationID + uFirstCell);
  if (any(greaterThanEqual(cell, min(imageSize(oLevel), ivec3(uEndCell))))) return;
  ivec3 base = 2 * cell;
  vec4 c[8];
  for (int i = 0; i < 8; ++i) c[i] = child(base + ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
#ifdef ANISOTROPIC
  imageStore(oLevel, cell, anisoReduce(c, uFace));
#else
  imageStore(oLevel, cell, boxMean8(c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]));
#endif
}
