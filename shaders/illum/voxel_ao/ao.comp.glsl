// voxel_ao's gather (illum/methods/voxel_ao.cpp): per gather pixel, N cosine rays of
// the kit's interleaved sets (../gather/gather.glsl) from the G-buffer point,
// started offset along the normal, traced through the binary grid with the
// chosen GLSL tracer up to the radius; AO = the fraction that reach it.
// With passThrough, a hit within a voxel diagonal of the receiver's tangent
// plane may be the receiver's own voxel and the ray goes on past it (up to
// three times), as nearfield's rays do.
// Output: rgb = AO, w = 1 where there is a surface, 0 elsewhere.
#define GATHER_DIRECTIONS
#include "shared/constants.glsl"
#include "shared/sampling.glsl"
#include "traverse/tracer.glsl"
#include "illum/gather/gather_pass.glsl"
#include "params.glsl"

layout(rgba32f, binding = IMAGE_OUTPUT) uniform image2D uAo;

layout(std140, binding = UBO_PASS) uniform Pass { VoxelAoParams pass; };

ivec2 gatherSize() { return imageSize(uAo); }

void gatherEmpty(ivec2 q) {
  imageStore(uAo, q, vec4(0.0f));
}

void gatherPixel(ivec2 q, vec3 p, vec3 n) {
  Basis frame = makeBasis(n);
  vec3 origin = p + n * pass.offset;
  int open = 0;
  for (int r = gather.batchFirst; r < gather.batchEnd; ++r) {
    vec3 d = gatherDirection(q, r, frame);
    ResumableRay ray = resumableRay(origin, d, pass.radius);
    while (true) {
      if (!nextHit(ray)) {
        ++open;
        break;
      }
      precise float height = dot(d, n) * hitDistance(ray) + pass.offset;  // of the hit above the receiver's plane
      if (pass.passThrough == 0 || height >= pass.voxelDiagonal || !passHit(ray, pass.voxelDiagonal)) break;
    }
  }
  imageStore(uAo, q, vec4(gatheredBefore(uAo, q).xyz + vec3(float(open) / float(gather.rays)), 1.0f));
}
