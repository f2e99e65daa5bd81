// G-buffer: world position (w = 1 where a surface was seen), shading normal
// turned towards the viewer (surfaces are two-sided, as in the reference) with
// the material index in w, textured albedo, and the triangle's geometric
// normal (the receiver plane of the shadow test, shaders/shared/light_maps.glsl)
// with w = 1 where the viewer sees the triangle's front (counter-clockwise)
// side, the side a one-sided emitter emits on (core/emitters.h).
#include "shared/constants.glsl"
#include "shared/sampling.glsl"
#include "shared/brdf.glsl"
#include "shared/environment.glsl"
#include "shared/gpu_scene.glsl"
in vec3 vPosition;
in vec3 vNormal;
in vec2 vUv;
flat in vec3 vGeometricNormal;
layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outAlbedo;
layout(location = 3) out vec4 outGeometricNormal;
void main() {
  int m = triMaterial[gl_PrimitiveID];
  vec3 n = normalize(vNormal);
  if (!gl_FrontFacing) n = -n;
  vec3 albedo = materials[m].albedoLayer.xyz;
  float layer = materials[m].albedoLayer.w;
  if (layer >= 0.0f) albedo *= texture(albedoTextures, vec3(vUv.x, 1.0f - vUv.y, layer)).xyz;
  outPosition = vec4(vPosition, 1.0f);
  outNormal = vec4(n, float(m));
  outAlbedo = vec4(albedo, 1.0f);
  outGeometricNormal = vec4(vGeometricNormal, gl_FrontFacing ? 1.0f : 0.0f);
}
