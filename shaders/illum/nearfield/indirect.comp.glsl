// VGI §5.1 near-field gathering, one invocation per indirect-buffer pixel:
// N cosine-distributed rays from the G-buffer point of the pixel's
// representative full-resolution texel, started `uOffset` world units along
// the normal (half a voxel diagonal by default; VGI's full diagonal clears
// every cell the local plane touches, at the cost of contact light — here
// the receiver's own voxels are passed instead, see main()),
// traced through the binary voxel grid up to the radius r; a hit is
// back-projected into every reflective shadow map and receives the stored
// radiance where the RSM sees the same surface (the ε rule); rays that leave r
// read the environment (directional occlusion) when uEnv is set.
// Directions: the gather kit's interleaved sets (../gather/gather.glsl).
//
// Output: rgb = mean radiance arriving along the rays (so the reflected
// indirect light of a diffuse surface is albedo × rgb), w = 1 where there is a
// surface, 0 elsewhere.
#include "../../shared/constants.glsl"
#include "../../shared/sampling.glsl"
#include "../../shared/brdf.glsl"
#include "../../shared/environment.glsl"
#include "../../shared/gpu_scene.glsl"
#include "../../shared/light_maps.glsl"
#include "../../traverse/tracer.glsl"
#define GATHER_DIRECTIONS
#include "../gather/gather.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = IMAGE_OUTPUT) uniform writeonly image2D uIndirect;

uniform float uRadius;       // r, world units
uniform float uOffset;       // start offset along the normal, world units
uniform float uVoxelDiagonal;
uniform int uEnv;
uniform int uRsmRes;
uniform int uPassThrough;     // 1: rays go on past empty-looking and own voxels (see main)
uniform int uRefine;          // back-projection: 0 the voxel entry (VGI), 1 the RSM surface's plane


// The RSM texel of light l that point y projects to: its face and texel, or
// face −1 outside every face or where the light saw nothing.
struct RsmTexel {
  int face;
  ivec3 texel;
  vec3 position, normal;
};
bool insideLightMap(int l, vec3 y) {
  vec2 uv = lightMapUv(lightFaces[lightFaceOf(l, y)], y);
  return uv.x >= 0.0f && uv.y >= 0.0f && uv.x <= 1.0f && uv.y <= 1.0f;
}
RsmTexel rsmTexelAt(int l, vec3 y) {
  RsmTexel r;
  r.face = lightFaceOf(l, y);
  vec2 uv = lightMapUv(lightFaces[r.face], y);
  r.texel = ivec3(min(ivec2(uv * float(uRsmRes)), ivec2(uRsmRes - 1)), r.face);
  vec4 P = texelFetch(lightPosition, r.texel, 0);
  if (uv.x < 0.0f || uv.y < 0.0f || uv.x > 1.0f || uv.y > 1.0f || P.w == 0.0f) r.face = -1;
  r.position = P.xyz;
  r.normal = texelFetch(lightNormal, r.texel, 0).xyz;
  return r;
}

// VGI's ε (shared/light_maps.glsl) for the surface a texel saw.
float rsmEpsilon(int l, RsmTexel r, float voxelTerm) {
  LightSample ls = sampleDeltaLight(lights[l], r.position);
  return backProjectionEpsilon(voxelTerm,
                               lightMapTexelWorld(lightFaces[r.face], lightMapDistance(lightFaces[r.face], r.position)),
                               dot(r.normal, ls.wi));
}

// Direct radiance leaving the surface the ray (o, d) hit in the voxel it
// entered at distance t, read back from every RSM.
//   uRefine 0, VGI §5.1: the voxel entry y = o + t·d is back-projected and
//     takes the texel's radiance when |y − p_rsm| < ε (ε ≥ the voxel diagonal,
//     as y lies up to a diagonal off the surface).
//   uRefine 1: the texel y projects to says which surface the light sees
//     there; the ray is intersected with that surface's plane, and the point
//     found (on the ray, on the surface) is back-projected again and tested
//     with the texel term of ε alone. The plane must be met near the hit
//     voxel (t − diag … t + 8·diag: a conservatively set voxel is often
//     entered far before the plane at grazing angles), within r, from the lit side
//     (a ray meeting the unlit back of a wall sees no RSM light); so voxel
//     quantisation no longer lets the ε test accept a neighbouring surface
//     or reject a lit one seen at a grazing angle.
struct BackProjection {
  vec3 radiance;
  bool seenThrough;  // a light sees past y: nothing is there (see main)
};
BackProjection backProject(vec3 o, vec3 d, float t) {
  precise vec3 y = o + t * d;
  vec3 sum = vec3(0.0f);
  bool through = false;
  for (int l = 0; l < lights.length(); ++l) {
    RsmTexel r = rsmTexelAt(l, y);
    if (r.face < 0) {
      through = through || texelFetch(lightPosition, r.texel, 0).w == 0.0f && insideLightMap(l, y);
      continue;
    }
    LightFace face = lightFaces[r.face];
    through = through || lightMapDistance(face, r.position) > lightMapDistance(face, y) + 1.5f * uVoxelDiagonal;
    if (uRefine == 0) {
      if (distance(y, r.position) < rsmEpsilon(l, r, uVoxelDiagonal)) sum += texelFetch(lightRadiance, r.texel, 0).xyz;
      continue;
    }
    // Up to three steps: a step that lands on another surface's texel
    // (small features: the first texel belongs to a neighbour) tries that one.
    for (int step = 0; step < 3; ++step) {
      float c = dot(d, r.normal);
      if (c >= -1e-4f) break;  // parallel to the plane, or meeting its unlit side
      precise float ts = dot(r.position - o, r.normal) / c;
      if (ts < t - uVoxelDiagonal || ts > t + 8.0f * uVoxelDiagonal || ts > uRadius) break;
      precise vec3 ys = o + ts * d;
      RsmTexel rs = rsmTexelAt(l, ys);
      if (rs.face < 0) break;
      if (distance(ys, rs.position) < rsmEpsilon(l, rs, 0.0f)) {
        sum += texelFetch(lightRadiance, rs.texel, 0).xyz;
        break;
      }
      r = rs;
    }
  }
  BackProjection b;
  b.radiance = sum;
  b.seenThrough = through && sum == vec3(0.0f);
  return b;
}

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(uIndirect);
  if (q.x >= size.x || q.y >= size.y) return;
  ivec2 px = representative(q, textureSize(gPosition, 0));
  vec4 P = texelFetch(gPosition, px, 0);
  if (P.w == 0.0f) {
    imageStore(uIndirect, q, vec4(0.0f));
    return;
  }
  vec3 n = normalize(texelFetch(gNormal, px, 0).xyz);
  Basis frame = makeBasis(n);
  vec3 origin = P.xyz + n * uOffset;
  vec3 sum = vec3(0.0f);
  for (int r = 0; r < uRays; ++r) {
    vec3 d = gatherDirection(q, r, frame);
    // With uPassThrough the ray goes on past a hit voxel, up to three times,
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
    ResumableRay ray = resumableRay(origin, d, uRadius);
    while (true) {
      if (!nextHit(ray)) {
        if (uEnv != 0) sum += gpuEnvironmentRadiance(d);
        break;
      }
      precise float t = hitDistance(ray);
      BackProjection b = backProject(origin, d, t);
      sum += b.radiance;
      precise float height = dot(d, n) * t + uOffset;  // of the hit above the receiver's plane
      bool ownBand = height < uVoxelDiagonal && b.radiance == vec3(0.0f);
      if (uPassThrough == 0 || !(b.seenThrough || ownBand) || !passHit(ray, uVoxelDiagonal)) break;
    }
  }
  imageStore(uIndirect, q, vec4(sum / float(uRays), 1.0f));
}
