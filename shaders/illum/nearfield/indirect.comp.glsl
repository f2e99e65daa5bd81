// VGI §5.1 near-field gathering, one invocation per indirect-buffer pixel:
// N cosine-distributed rays from the G-buffer point of the pixel's
// representative full-resolution texel, started `offset` world units along
// the normal (half a voxel diagonal by default; VGI's full diagonal clears
// every cell the local plane touches, at the cost of contact light — here
// the receiver's own voxels are passed instead, see main()),
// traced through the binary voxel grid up to the radius r; a hit is
// back-projected into every reflective shadow map and receives the stored
// radiance where the RSM sees the same surface (the ε rule, rsmBackProject in
// shared/light_maps.glsl); rays that leave r
// read the environment (directional occlusion) when env is set.
// Directions: the gather kit's interleaved sets (../gather/gather.glsl).
//
// Output: rgb = mean radiance arriving along the rays (so the reflected
// indirect light of a diffuse surface is albedo × rgb), w = 1 where there is a
// surface, 0 elsewhere.
#include "shared/constants.glsl"
#include "shared/sampling.glsl"
#include "shared/brdf.glsl"
#include "shared/environment.glsl"
#include "shared/gpu_scene.glsl"
#include "shared/light_maps.glsl"
#include "traverse/tracer.glsl"
#define GATHER_DIRECTIONS
#include "illum/gather/gather_pass.glsl"
#include "params.glsl"

layout(rgba32f, binding = IMAGE_OUTPUT) uniform image2D uIndirect;

layout(std140, binding = UBO_PASS) uniform Pass { NearFieldPassParams pass; };


ivec2 gatherSize() { return imageSize(uIndirect); }

void gatherEmpty(ivec2 q) {
  imageStore(uIndirect, q, vec4(0.0f));
}

void gatherPixel(ivec2 q, vec3 p, vec3 n) {
  Basis frame = makeBasis(n);
  vec3 origin = p + n * pass.offset;
  vec3 sum = vec3(0.0f);
  for (int r = gather.batchFirst; r < gather.batchEnd; ++r) {
    vec3 d = gatherDirection(q, r, frame);
    // With pass.passThrough the ray goes on past a hit voxel, up to three times,
    // when (a) a light sees through its entry point — nothing is there (a
    // conservatively set voxel of a thin feature) — or (b) it lies within a
    // voxel diagonal of the receiver's tangent plane and gives no light: it may
    // be the receiver's own voxel. (b) is what lets rays start half a diagonal
    // off the surface instead of VGI's full diagonal, so contact light in
    // corners and at small features is not lost (Sibenik: energy 0.82 → 0.88).
    // (With resumed rays the hierarchical and dda programs still differ on a
    // few pixels, though the tracers agree on such rays in tests/traverse — an
    // open question, see NearField.TracerIsAParameter….) A ray passed on
    // beyond the radius reads the environment, like one that met nothing.
    ResumableRay ray = resumableRay(origin, d, pass.radius);
    while (true) {
      if (!nextHit(ray)) {
        if (pass.env != 0) sum += gpuEnvironmentRadiance(d);
        break;
      }
      precise float t = hitDistance(ray);
      BackProjection b = rsmBackProject(origin, d, t, pass.voxelDiagonal, pass.radius, pass.backProjection == BACK_PROJECTION_PLANE);
      sum += b.radiance;
      precise float height = dot(d, n) * t + pass.offset;  // of the hit above the receiver's plane
      bool ownBand = height < pass.voxelDiagonal && b.radiance == vec3(0.0f);
      if (pass.passThrough == 0 || !(b.seenThrough || ownBand) || !passHit(ray, pass.voxelDiagonal)) break;
    }
  }
  imageStore(uIndirect, q, vec4(gatheredBefore(uIndirect, q).xyz + sum / float(gather.rays), 1.0f));
}
