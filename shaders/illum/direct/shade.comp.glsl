// Deferred direct lighting: per pixel, every delta light through the shared
// light and BRDF kernels, visibility from the shadow maps, plus emission; the
// environment where no surface was seen. Adds one jittered sample into uAccum.
#include "../../shared/constants.glsl"
#include "../../shared/sampling.glsl"
#include "../../shared/brdf.glsl"
#include "../../shared/environment.glsl"
#include "../../shared/gpu_scene.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D gPosition;
layout(binding = 1) uniform sampler2D gNormal;
layout(binding = 2) uniform sampler2D gAlbedo;
layout(binding = 3) uniform samplerCubeArray shadowCubes;
layout(binding = 4) uniform sampler2DArray shadowPlanes;
layout(rgba32f, binding = 0) uniform image2D uAccum;

uniform vec3 uCameraPosition;
uniform mat4 uInvViewProj;
uniform float uShadowRes;
uniform float uShadowBias;     // in shadow-map texels
uniform float uNormalOffset;   // in shadow-map texels
uniform mat4 uPlaneViewProj[MAX_DIRECTIONAL];
uniform float uPlaneTexelWorld[MAX_DIRECTIONAL];
uniform vec3 uPlaneOrigin[MAX_DIRECTIONAL];

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(uAccum);
  if (px.x >= size.x || px.y >= size.y) return;
  vec4 P = texelFetch(gPosition, px, 0);
  vec3 L = vec3(0.0f);
  if (P.w == 0.0f) {
    vec2 ndc = (vec2(px) + 0.5f) / vec2(size) * 2.0f - 1.0f;  // inverse of the jittered matrix
    vec4 far = uInvViewProj * vec4(ndc, 1.0f, 1.0f);
    L = gpuEnvironmentRadiance(normalize(far.xyz / far.w - uCameraPosition));
  } else {
    vec3 p = P.xyz;
    vec4 N = texelFetch(gNormal, px, 0);
    vec3 n = normalize(N.xyz);
    int m = int(N.w + 0.5f);
    BrdfParams brdf = gpuMaterialBrdf(m, texelFetch(gAlbedo, px, 0).xyz);
    vec3 wo = normalize(uCameraPosition - p);
    L = materials[m].emission.xyz;
    int cubeSlot = 0;
    int planeSlot = 0;
    for (int i = 0; i < lights.length(); ++i) {
      PackedLight light = lights[i];
      bool directional = uint(light.positionType.w + 0.5f) == LIGHT_DIRECTIONAL;
      LightSample ls = sampleDeltaLight(light, p);
      float cosI = dot(ls.wi, n);
      bool lit = cosI > 0.0f && (ls.radiance.x + ls.radiance.y + ls.radiance.z) > 0.0f;
      if (lit && !directional) {
        // Cube face: 90° over uShadowRes texels, so one texel spans 2·d/res in world.
        float texel = 2.0f * ls.dist / uShadowRes;
        vec3 q = p + n * (uNormalOffset * texel);
        vec3 d = q - light.positionType.xyz;
        float stored = texture(shadowCubes, vec4(d, float(cubeSlot))).x;
        lit = length(d) - uShadowBias * texel / max(cosI, 0.2f) <= stored;
      } else if (lit) {
        float texel = uPlaneTexelWorld[planeSlot];
        vec3 q = p + n * (uNormalOffset * texel);
        vec4 c = uPlaneViewProj[planeSlot] * vec4(q, 1.0f);
        vec2 uv = c.xy * 0.5f + 0.5f;
        float stored = texture(shadowPlanes, vec3(uv, float(planeSlot))).x;
        float depth = dot(q - uPlaneOrigin[planeSlot], light.directionCosCone.xyz);
        lit = depth - uShadowBias * texel / max(cosI, 0.2f) <= stored;
      }
      if (directional) planeSlot++;
      else cubeSlot++;
      if (lit) L += evalBrdf(brdf, n, wo, ls.wi) * ls.radiance * cosI;
    }
  }
  imageStore(uAccum, px, imageLoad(uAccum, px) + vec4(L, 1.0f));
}
