// VGI §5.2 voxel path tracing (illum/methods/voxelpath.cpp), one invocation per pixel
// and one path per sample. The primary vertex x0 is the G-buffer's (its
// direct light is already in the sample image: the deferred pass); from it a
// path of up to maxDepth − 1 bounces: the next direction by BRDF importance
// sampling (Lambert cosine, normalised Phong lobe: shared/brdf.glsl), the
// first hit through the binary voxel grid (the chosen GLSL tracer), the
// normal and BRDF there from the multi-valued grids' 3D textures (the hit
// voxel's mean), direct light there by RSM back-projection for the diffuse
// part (shared/light_maps.glsl: rsmBackProject, the ε rule) and evaluated
// with light-map visibility for the glossy lobe, as §5.2 says; Russian
// roulette after rrDepth bounces, as the reference's path integrator.
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
// Output: the sample image += the path's radiance; with writeDirect /
// writeIndirect the AOVs get the direct part (the deferred pass's, plus the
// environment seen by x0's own bounce ray — direct light of x0, as in the
// reference's split) and the rest.
#include "shared/constants.glsl"
#include "shared/sampling.glsl"
#include "shared/brdf.glsl"
#include "shared/environment.glsl"
#include "shared/gpu_scene.glsl"
#include "shared/gbuffer.glsl"
#include "shared/light_maps.glsl"
#include "shared/value_textures.glsl"
#include "traverse/tracer.glsl"
#include "illum/voxel_hits.glsl"
#include "params.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = IMAGE_SAMPLE) uniform image2D uSample;  // holds the direct light; += the path
layout(rgba32f, binding = IMAGE_SAMPLE_AOV0) uniform writeonly image2D uIndirectAov;
layout(rgba32f, binding = IMAGE_SAMPLE_AOV1) uniform writeonly image2D uDirectAov;
layout(std140, binding = UBO_PASS) uniform Pass { VoxelPathParams pass; };

// The glossy lobe's direct light at v toward wo, through the light maps.
vec3 glossyDirect(Vertex v, vec3 wo) {
  if (v.brdf.ks.x + v.brdf.ks.y + v.brdf.ks.z <= 0.0f) return vec3(0.0f);
  BrdfParams lobe = v.brdf;
  lobe.albedo = vec3(0.0f);
  return lightMapsDirect(lobe, v.p, v.n, v.n, wo, pass.shadowBias, pass.normalOffset);
}

vec3 clampContribution(vec3 c) {
  if (pass.clampMax <= 0.0f) return c;
  float m = max(c.x, max(c.y, c.z));
  return m > pass.clampMax ? c * (pass.clampMax / m) : c;
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(uSample);
  if (px.x >= size.x || px.y >= size.y) return;
  vec4 direct = imageLoad(uSample, px);
  vec3 indirect = vec3(0.0f);
  vec4 P = texelFetch(gPosition, px, 0);
  if (P.w != 0.0f && pass.maxDepth > 1) {
    vec4 N = texelFetch(gNormal, px, 0);
    Vertex x;
    x.p = P.xyz;
    x.n = normalize(N.xyz);
    x.brdf = gpuMaterialBrdf(int(N.w), texelFetch(gAlbedo, px, 0).xyz);
    if (hits.glossy == 0) x.brdf.ks = vec3(0.0f);
    vec3 wo = normalize(pass.cameraPosition.xyz - x.p);
    uint rng = rngSeed(uint(px.y * size.x + px.x), pass.sampleIndex, pass.seed);
    vec3 beta = vec3(1.0f);
    for (int depth = 0; depth + 1 < pass.maxDepth; ++depth) {
      vec3 u = vec3(rngNext(rng), rngNext(rng), rngNext(rng));
      vec3 wi = sampleBrdf(x.brdf, x.n, wo, u);
      float pdf = brdfPdf(x.brdf, x.n, wo, wi);
      float cosI = dot(wi, x.n);
      if (!(pdf > 0.0f) || cosI <= 0.0f) break;
      beta *= evalBrdf(x.brdf, x.n, wo, wi) * (cosI / pdf);
      if (depth + 1 >= pass.rrDepth) {
        float q = russianRouletteQ(beta);
        if (rngNext(rng) < q) break;
        beta /= 1.0f - q;
      }
      vec3 o = x.p + x.n * hits.offset;
      float t;
      uvec3 voxel;
      BackProjection b;
      if (!trace(o, wi, x.n, t, voxel, b)) {
        if (pass.env != 0) {
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
  if (pass.writeDirect != 0) imageStore(uDirectAov, px, vec4(direct.xyz, 1.0f));
  if (pass.writeIndirect != 0) imageStore(uIndirectAov, px, vec4(indirect, 1.0f));
}
