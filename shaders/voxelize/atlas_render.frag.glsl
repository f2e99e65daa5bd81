// Atlas texels: world position (w = 1: valid) and the triangle that wrote it;
// with MULTI_VALUED also the world normal, textured albedo and glossy (ks,
// exponent) for the multi-valued grids. Edge fragments (uClampToTriangle) are
// interpolated at their centre's projection on the line, which overshoots the
// edge's ends by up to half a texel: they are pulled back onto their triangle,
// so every point lies on the surface.
#include "../shared/closest_point.glsl"
// Outside #ifdef MULTI_VALUED: the library includes a file once, at its first #include line.
#include "../shared/bindings.glsl"
#ifdef MULTI_VALUED
#include "../shared/constants.glsl"
#include "../shared/sampling.glsl"
#include "../shared/brdf.glsl"
#include "../shared/environment.glsl"
#include "../shared/gpu_scene.glsl"
uniform int uMaterial;
layout(location = 2) out vec4 outNormal;
layout(location = 3) out vec4 outAlbedo;
layout(location = 4) out vec4 outGlossy;
#endif
in vec3 vPosition;
in vec3 vNormal;
in vec2 vTexUv;
flat in int vTriangle;
uniform mat4 uModel;
uniform int uClampToTriangle;
layout(std430, binding = BINDING_ATLAS_CORNERS) readonly buffer Corners { float corners[]; };  // the VBO: ATLAS_VERTEX_FLOATS per corner
layout(location = 0) out vec4 outPosition;
layout(location = 1) out int outTriangle;
vec3 corner(int i) {
  int o = ATLAS_VERTEX_FLOATS * i;
  return (uModel * vec4(corners[o], corners[o + 1], corners[o + 2], 1.0f)).xyz;
}
void main() {
  vec3 p = vPosition;
  if (uClampToTriangle != 0)
    p = closestPointOnTriangle(p, corner(3 * vTriangle), corner(3 * vTriangle + 1), corner(3 * vTriangle + 2));
  outPosition = vec4(p, 1.0f);
  outTriangle = vTriangle;
#ifdef MULTI_VALUED
  vec3 albedo = materials[uMaterial].albedoLayer.xyz;
  float layer = materials[uMaterial].albedoLayer.w;
  if (layer >= 0.0f) albedo *= texture(albedoTextures, vec3(vTexUv.x, 1.0f - vTexUv.y, layer)).xyz;
  vec3 n = vNormal;
  outNormal = vec4(dot(n, n) > 0.0f ? normalize(n) : vec3(0.0f), 1.0f);
  outAlbedo = vec4(albedo, 1.0f);
  outGlossy = materials[uMaterial].ksExponent;
#endif
}
