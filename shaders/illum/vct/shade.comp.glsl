// vct's full-resolution pass (illum/methods/vct.cpp), after the kit's composite of
// the diffuse cones: per pixel
//   specular (specular): one cone along the reflected view direction, its
//     half-angle from the Phong exponent (phongConeTanHalf), reflected as
//     ks · (e + 2)/(e + 1) · cos θ_r · L (the normalised lobe's integral for a
//     lobe inside the hemisphere);
//   soft shadows (shadows): the delta lights' direct light with a cone of
//     half-angle shadowTanHalf toward each light for visibility, replacing
//     the shadow-mapped direct light of the sample (D_cone − D_shadowmap, the
//     latter through the direct pass' own lightMapsDirect);
//   the AO output from the upsampled AO of the diffuse pass.
#include "shared/constants.glsl"
#include "shared/sampling.glsl"
#include "shared/brdf.glsl"
#include "shared/environment.glsl"
#include "shared/gpu_scene.glsl"
#include "shared/light_maps.glsl"
#include "shared/gbuffer.glsl"
#include "cones.glsl"
#include "params.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = IMAGE_SAMPLE) uniform image2D uSample;
layout(rgba32f, binding = IMAGE_SAMPLE_AOV0) uniform image2D uIndirectAov;
layout(rgba32f, binding = IMAGE_SAMPLE_AOV1) uniform image2D uDirectAov;
layout(rgba32f, binding = IMAGE_SAMPLE_AOV2) uniform writeonly image2D uAoAov;
layout(rgba32f, binding = IMAGE_SAMPLE_AOV3) uniform writeonly image2D uSpecularAov;
layout(binding = TEXUNIT_PASS_INPUT) uniform sampler2D uAoFull;
layout(std140, binding = UBO_PASS) uniform Pass { VctShadeParams pass; };

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(uSample);
  if (px.x >= size.x || px.y >= size.y) return;
  vec4 P = texelFetch(gPosition, px, 0);
  if (P.w == 0.0f) {
    if (pass.writeAo != 0) imageStore(uAoAov, px, vec4(0.0f, 0.0f, 0.0f, 1.0f));
    if (pass.writeSpecular != 0) imageStore(uSpecularAov, px, vec4(0.0f, 0.0f, 0.0f, 1.0f));
    return;
  }
  vec3 p = P.xyz;
  vec4 N = texelFetch(gNormal, px, 0);
  vec3 n = normalize(N.xyz);
  vec3 ng = texelFetch(gGeometricNormal, px, 0).xyz;
  int m = int(N.w + 0.5f);
  BrdfParams brdf = gpuMaterialBrdf(m, texelFetch(gAlbedo, px, 0).xyz);
  vec3 wo = normalize(pass.cameraPosition.xyz - p);
  vec3 apex = p + n * pass.offset;
  vec3 specular = vec3(0.0f);
  if (pass.specular != 0 && brdf.ks.x + brdf.ks.y + brdf.ks.z > 0.0f) {
    vec3 r = reflectAbout(wo, n);
    float cr = dot(r, n);
    if (cr > 0.0f) {
      ConeResult c = traceCone(apex, r, phongConeTanHalf(brdf.exponent), pass.maxDistance, 0.0f, 0.0f, pass.skipEmpty != 0, pass.offset, pass.guard != 0 ? cr : -1.0f);
      vec3 L = c.radiance;
      if (pass.env != 0 && c.escaped > 0.0f) L += (1.0f - c.opacity) * gpuEnvironmentRadiance(r);
      specular = brdf.ks * ((brdf.exponent + 2.0f) / (brdf.exponent + 1.0f) * cr) * L;
    }
  }
  vec3 directChange = vec3(0.0f);
  if (pass.shadows != 0) {
    vec3 coneDirect = vec3(0.0f);
    for (int i = 0; i < uLightCount; ++i) {
      LightSample ls = sampleDeltaLight(lights[i], p);
      float cosI = dot(ls.wi, n);
      if (cosI <= 0.0f || ls.radiance.x + ls.radiance.y + ls.radiance.z <= 0.0f) continue;
      // Stop pass.shadowStop cone widths (at least voxel diagonals) short of the light: a
      // light just under a ceiling would otherwise be shadowed by it (Cornell: direct
      // energy 0.64 at 1 width, 0.95 at 4).
      float len = min(ls.dist, 1e6f);
      len -= pass.shadowStop * max(2.0f * len * pass.shadowTanHalf, pass.voxelDiagonal);
      float visibility = 1.0f;
      if (len > 0.0f) visibility = 1.0f - traceCone(apex, ls.wi, pass.shadowTanHalf, len, 0.0f, 0.0f, false, pass.offset, pass.guard != 0 ? cosI : -1.0f).opacity;
      coneDirect += evalBrdf(brdf, n, wo, ls.wi) * ls.radiance * cosI * visibility;
    }
    directChange = coneDirect - lightMapsDirect(brdf, p, n, ng, wo, pass.shadowBias, pass.normalOffset);
  }
  vec4 s = imageLoad(uSample, px);
  imageStore(uSample, px, vec4(s.xyz + specular + directChange, 1.0f));
  if (pass.writeIndirect != 0) imageStore(uIndirectAov, px, vec4(imageLoad(uIndirectAov, px).xyz + specular, 1.0f));
  if (pass.writeDirect != 0) imageStore(uDirectAov, px, vec4(imageLoad(uDirectAov, px).xyz + directChange, 1.0f));
  if (pass.writeAo != 0) imageStore(uAoAov, px, vec4(vec3(texelFetch(uAoFull, px, 0).x), 1.0f));
  if (pass.writeSpecular != 0) imageStore(uSpecularAov, px, vec4(specular, 1.0f));
}
