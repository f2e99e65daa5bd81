// VGI §5.2 voxel path tracing (illum/voxelpath.cpp), one invocation per pixel
// and one path per sample. The primary vertex x0 is the G-buffer's (its
// direct light is already in the sample image: the deferred pass); from it a
// path of up to uMaxDepth − 1 bounces: the next direction by BRDF importance
// sampling (Lambert cosine, normalised Phong lobe: shared/brdf.glsl), the
// first hit through the binary voxel grid (the chosen GLSL tracer), the
// normal and BRDF there from the multi-valued grids' 3D textures (the hit
// voxel's mean), direct light there by RSM back-projection for the diffuse
// part (shared/light_maps.glsl: rsmBackProject, the ε rule) and evaluated
// with light-map visibility for the glossy lobe, as §5.2 says; Russian
// roulette after uRrDepth bounces, as the reference's path integrator.
//
// The paper's texture-per-bounce propagation (Fig. 8: hit data stored per
// depth, then energy carried back) was a 2011 constraint; this loop carries
// the throughput forward and adds each vertex's direct light as it goes —
// the same estimator (Σ_j β_j · L_direct(x_j)), in one pass, without l
// textures.
//
// Emission met by a path is not added: every emissive mesh is already a light
// of the sample (SceneResources: one emitter point per sample as a spot light
// with its RSM), so its light reaches each vertex through the back-projection;
// adding Le at hits as well would count it twice (the reference counts it
// once, by MIS between the two strategies).
//
// Output: the sample image += the path's radiance; with uWriteDirect /
// uWriteIndirect the AOVs get the direct part (the deferred pass's, plus the
// environment seen by x0's own bounce ray — direct light of x0, as in the
// reference's split) and the rest.
#include "../../shared/constants.glsl"
#include "../../shared/sampling.glsl"
#include "../../shared/brdf.glsl"
#include "../../shared/environment.glsl"
#include "../../shared/gpu_scene.glsl"
#include "../../shared/gbuffer.glsl"
#include "../../shared/light_maps.glsl"
#include "../../shared/value_textures.glsl"
#include "../../traverse/tracer.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = IMAGE_SAMPLE) uniform image2D uSample;  // holds the direct light; += the path
layout(rgba32f, binding = IMAGE_SAMPLE_AOV0) uniform writeonly image2D uIndirectAov;
layout(rgba32f, binding = IMAGE_SAMPLE_AOV1) uniform writeonly image2D uDirectAov;
uniform int uWriteIndirect, uWriteDirect;

uniform vec3 uCameraPosition;
uniform int uMaxDepth;        // 1: direct light only
uniform int uRrDepth;         // bounces before Russian roulette
uniform float uOffset;        // ray start offset along the normal, world units
uniform float uVoxelDiagonal;
uniform float uTraceLength;   // longer than any ray through the grid
uniform float uClamp;         // > 0: each vertex's contribution clamped to this (max component)
uniform int uEnv;             // rays leaving the grid read the environment
uniform int uGlossy;          // 0: the Phong lobes are dropped (diffuse only)
uniform int uRefine;          // back-projection: 0 the voxel entry (VGI), 1 the RSM surface's plane
uniform int uPassThrough;     // pass hits in the start's own band (see trace())
uniform int uHitPoint;        // 0 voxel entry, 1 voxel centre, 2 on the plane of the voxel's mean normal
uniform float uShadowBias;    // light-map lookups at hits (glossy lobe), texels
uniform float uNormalOffset;
uniform uint uSeed;
uniform uint uSampleIndex;

// A path vertex as the grid knows it.
struct Vertex {
  vec3 p, n;
  BrdfParams brdf;
};

// The first voxel hit along (o, d), and its RSM back-projection. With
// uPassThrough the ray goes on past a hit (up to kMaxPasses times) within a
// voxel diagonal of the start's tangent plane — the start is only half a
// diagonal off its surface, so it may be the start's own voxel — when the
// cell's mean normal is the start's up to sign (the grid keeps the mesh's
// normals, which need not face the viewer) or the hit gives no light.
// Measured against reference path (docs/BENCHMARKS.md): the normal rule
// alone loses 2.5 % of the indirect light (in corners); adding nearfield's
// pass of voxels a light sees through loses 7 % on the Cornell box (a path
// that passes them goes on past real, unlit surfaces); this rule: 1.1 % (room) to 1.5 % (Cornell box).
bool trace(vec3 o, vec3 d, vec3 n, out float t, out uvec3 voxel, out BackProjection b) {
  ResumableRay ray = resumableRay(o, d, uTraceLength);
  while (nextHit(ray)) {
    t = hitDistance(ray);
    voxel = ray.hit.voxel;
    precise float height = dot(d, n) * t + uOffset;
    bool band = uPassThrough != 0 && height < uVoxelDiagonal;
    // The normal rule needs no back-projection: a band hit it passes costs one fetch.
    vec4 nv = band ? texelFetch(valueNormal, ivec3(voxel), 0) : vec4(0.0f);
    if (band && abs(dot(nv.xyz, n)) > 0.8f * length(nv.xyz) && passHit(ray, uVoxelDiagonal)) continue;
    b = rsmBackProject(o, d, t, uVoxelDiagonal, uTraceLength, uRefine != 0);
    if (band && b.radiance == vec3(0.0f) && passHit(ray, uVoxelDiagonal)) continue;
    return true;
  }
  return false;
}

// The hit vertex in voxel `voxel`, entered at distance t along (o, d).
// Returns false where the grid holds no values there (a cell the binary grid
// set but no atlas point reached): the path ends.
bool hitVertex(vec3 o, vec3 d, float t, uvec3 voxel, out Vertex v) {
  ivec3 c = ivec3(voxel);
  float occ = texelFetch(valueOccupancy, c, 0).x;
  if (occ <= 0.0f) return false;
  vec3 mean = texelFetch(valueNormal, c, 0).xyz / occ;
  float len = length(mean);
  // Two sides of a wall in one cell cancel: the side the ray meets is the one facing it.
  vec3 n = len > 1e-3f ? mean / len : -d;
  if (dot(n, d) > 0.0f) n = -n;
  v.n = n;
  v.brdf.albedo = texelFetch(valueAlbedo, c, 0).xyz / occ;
  vec4 g = texelFetch(valueGlossy, c, 0) / occ;
  v.brdf.ks = uGlossy != 0 ? vec3(g.x, g.y, g.z) : vec3(0.0f);
  v.brdf.exponent = decodeExponent(g.w);
  precise vec3 entry = o + t * d;
  v.p = entry;
  if (uHitPoint != 0) {
    GridParams grid = gridFromUniforms();
    vec3 centre = gridToWorld(grid, vec3(voxel) + vec3(0.5f));
    v.p = centre;
    if (uHitPoint == 2) {
      // The plane through the centre with the mean normal, met within the voxel.
      float cd = dot(d, n);
      if (cd < -1e-3f) {
        float ts = clamp(dot(centre - o, n) / cd, t, t + uVoxelDiagonal);
        v.p = o + ts * d;
      } else {
        v.p = entry;
      }
    }
  }
  return true;
}

// The glossy lobe's direct light at v toward wo, through the light maps.
vec3 glossyDirect(Vertex v, vec3 wo) {
  if (v.brdf.ks.x + v.brdf.ks.y + v.brdf.ks.z <= 0.0f) return vec3(0.0f);
  BrdfParams lobe = v.brdf;
  lobe.albedo = vec3(0.0f);
  return lightMapsDirect(lobe, v.p, v.n, v.n, wo, uShadowBias, uNormalOffset);
}

vec3 clampContribution(vec3 c) {
  if (uClamp <= 0.0f) return c;
  float m = max(c.x, max(c.y, c.z));
  return m > uClamp ? c * (uClamp / m) : c;
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(uSample);
  if (px.x >= size.x || px.y >= size.y) return;
  vec4 direct = imageLoad(uSample, px);
  vec3 indirect = vec3(0.0f);
  vec4 P = texelFetch(gPosition, px, 0);
  if (P.w != 0.0f && uMaxDepth > 1) {
    vec4 N = texelFetch(gNormal, px, 0);
    Vertex x;
    x.p = P.xyz;
    x.n = normalize(N.xyz);
    x.brdf = gpuMaterialBrdf(int(N.w), texelFetch(gAlbedo, px, 0).xyz);
    if (uGlossy == 0) x.brdf.ks = vec3(0.0f);
    vec3 wo = normalize(uCameraPosition - x.p);
    uint rng = rngSeed(uint(px.y * size.x + px.x), uSampleIndex, uSeed);
    vec3 beta = vec3(1.0f);
    for (int depth = 0; depth + 1 < uMaxDepth; ++depth) {
      vec3 u = vec3(rngNext(rng), rngNext(rng), rngNext(rng));
      vec3 wi = sampleBrdf(x.brdf, x.n, wo, u);
      float pdf = brdfPdf(x.brdf, x.n, wo, wi);
      float cosI = dot(wi, x.n);
      if (!(pdf > 0.0f) || cosI <= 0.0f) break;
      beta *= evalBrdf(x.brdf, x.n, wo, wi) * (cosI / pdf);
      if (depth + 1 >= uRrDepth) {
        float q = max(0.05f, 1.0f - max(beta.x, max(beta.y, beta.z)));
        if (rngNext(rng) < q) break;
        beta /= 1.0f - q;
      }
      vec3 o = x.p + x.n * uOffset;
      float t;
      uvec3 voxel;
      BackProjection b;
      if (!trace(o, wi, x.n, t, voxel, b)) {
        if (uEnv != 0) {
          vec3 e = clampContribution(beta * gpuEnvironmentRadiance(wi));
          // The environment seen from x0 is x0's direct light.
          if (depth == 0) direct.xyz += e;
          else indirect += e;
        }
        break;
      }
      Vertex y;
      if (!hitVertex(o, wi, t, voxel, y)) break;
      vec3 Ld = b.radiance + glossyDirect(y, -wi);
      indirect += clampContribution(beta * Ld);
      x = y;
      wo = -wi;
    }
  }
  imageStore(uSample, px, vec4(direct.xyz + indirect, 1.0f));
  if (uWriteDirect != 0) imageStore(uDirectAov, px, vec4(direct.xyz, 1.0f));
  if (uWriteIndirect != 0) imageStore(uIndirectAov, px, vec4(indirect, 1.0f));
}
