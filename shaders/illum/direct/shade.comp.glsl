// Deferred direct lighting: per pixel, every delta light through the shared
// light and BRDF kernels, visibility from the shadow maps, plus emission; the
// environment where no surface was seen. Writes one jittered sample into uSample
// (the sample loop accumulates it). With DIRECT_SENDER also the diffuse direct light alone (no
// emission, the diffuse lobe: what a surface sends every way) into uSender, 0 where no surface was
// seen: the senders of the screen-space methods (ssdo).
#include "shared/constants.glsl"
#include "shared/sampling.glsl"
#include "shared/brdf.glsl"
#include "shared/environment.glsl"
#include "shared/gpu_scene.glsl"
#include "shared/light_maps.glsl"
#include "shared/gbuffer.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = IMAGE_SAMPLE) uniform writeonly image2D uSample;
#ifdef DIRECT_SENDER
layout(rgba32f, binding = IMAGE_OUTPUT2) uniform writeonly image2D uSender;
#endif

uniform vec3 uCameraPosition;
uniform mat4 uInvViewProj;
uniform float uShadowBias;     // in shadow-map texels
uniform float uNormalOffset;   // in shadow-map texels

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(uSample);
  if (px.x >= size.x || px.y >= size.y) return;
  vec4 P = texelFetch(gPosition, px, 0);
  vec3 L = vec3(0.0f);
  vec3 sender = vec3(0.0f);
  if (P.w == 0.0f) {
    vec2 ndc = (vec2(px) + 0.5f) / vec2(size) * 2.0f - 1.0f;  // inverse of the jittered matrix
    vec4 q = uInvViewProj * vec4(ndc, 1.0f, 1.0f);  // a point on the pixel's ray (reversed-Z: the near plane)
    L = gpuEnvironmentRadiance(normalize(q.xyz / q.w - uCameraPosition));
  } else {
    vec3 p = P.xyz;
    vec4 N = texelFetch(gNormal, px, 0);
    vec3 n = normalize(N.xyz);
    vec4 NG = texelFetch(gGeometricNormal, px, 0);
    vec3 ng = NG.xyz;
    int m = int(N.w + 0.5f);
    BrdfParams brdf = gpuMaterialBrdf(m, texelFetch(gAlbedo, px, 0).xyz);
    vec3 wo = normalize(uCameraPosition - p);
    // One-sided emitters (emission.w = 0) emit on their front side (NG.w = 1).
    if (materials[m].emission.w > 0.5f || NG.w > 0.5f) L = materials[m].emission.xyz;
    vec3 reflected = lightMapsDirect(brdf, p, n, ng, wo, uShadowBias, uNormalOffset);
    L += reflected;
#ifdef DIRECT_SENDER
    sender = brdf.ks == vec3(0.0f) ? reflected
                                   : lightMapsDirect(diffusePart(brdf), p, n, ng, wo, uShadowBias, uNormalOffset);
#endif
  }
  imageStore(uSample, px, vec4(L, 1.0f));
#ifdef DIRECT_SENDER
  imageStore(uSender, px, vec4(sender, 1.0f));
#endif
}
