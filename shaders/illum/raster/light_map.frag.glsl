// One face of a light map: the distance the shadow test compares against and,
// with REFLECTIVE defined (a reflective shadow map, VGI §5.1), the surface's
// position, normal (turned towards the light) and the direct radiance it
// reflects diffusely: albedo/π · E, evaluated with the shared light kernels.
#include "shared/constants.glsl"
#include "shared/sampling.glsl"
#include "shared/brdf.glsl"
#include "shared/environment.glsl"
#include "shared/gpu_scene.glsl"
in vec3 vPosition;
in vec3 vNormal;
in vec2 vUv;
flat in vec3 vGeometricNormal;
uniform vec3 uEye;
uniform vec3 uAxis;
uniform int uOrthographic;
uniform int uLight;
layout(location = 0) out float outDistance;
#ifdef REFLECTIVE
layout(location = 1) out vec4 outPosition;
layout(location = 2) out vec4 outNormal;
layout(location = 3) out vec4 outRadiance;
#endif
void main() {
  outDistance = uOrthographic != 0 ? dot(vPosition - uEye, uAxis) : length(vPosition - uEye);
#ifdef REFLECTIVE
  int m = triMaterial[gl_PrimitiveID];
  vec3 albedo = materials[m].albedoLayer.xyz;
  float layer = materials[m].albedoLayer.w;
  if (layer >= 0.0f) albedo *= texture(albedoTextures, vec3(vUv.x, 1.0f - vUv.y, layer)).xyz;
  LightSample ls = sampleDeltaLight(lights[uLight], vPosition);
  vec3 n = normalize(vNormal);
  if (dot(n, ls.wi) < 0.0f) n = -n;  // two-sided, as everywhere
  float cosI = max(dot(n, ls.wi), 0.0f);
  outPosition = vec4(vPosition, 1.0f);
  outNormal = vec4(n, 0.0f);
  outRadiance = vec4(albedo * INV_PI * ls.radiance * cosI, 1.0f);
#endif
}
