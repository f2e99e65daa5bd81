// Atlas texels: position as an offset from the grid's origin (w = 1: valid; see
// atlas_render.vert.glsl) and the triangle that wrote it;
// with MULTI_VALUED also the world normal, textured albedo and glossy (ks,
// exponent) for the multi-valued grids, and with VALUE_RADIANCE the diffuse
// direct light leaving the point (VGI §3, Table 2): every light of the bound
// lights SSBO through its light map (shared/lights, light_maps), the surface
// taken two-sided (the side facing each light), emission excluded (emitters
// are lights of their own); the pass's maximum goes to an SSBO (atomicMax on
// the float bits, which order like the floats for non-negative values).
// Edge fragments (uClampToTriangle) are
// interpolated at their centre's projection on the line, which overshoots the
// edge's ends by up to half a texel: they are pulled back onto their triangle,
// so every point lies on the surface.
#include "shared/closest_point.glsl"
// Outside #ifdef MULTI_VALUED: the library includes a file once, at its first #include line.
#include "shared/bindings.glsl"
#ifdef MULTI_VALUED
#include "shared/constants.glsl"
#include "shared/sampling.glsl"
#include "shared/brdf.glsl"
#include "shared/environment.glsl"
#include "shared/gpu_scene.glsl"
uniform int uMaterial;
layout(location = 2) out vec4 outNormal;
layout(location = 3) out vec4 outAlbedo;
layout(location = 4) out vec4 outGlossy;
#endif
#ifdef VALUE_RADIANCE
#include "shared/light_maps.glsl"
layout(location = 5) out vec4 outRadiance;
layout(std430, binding = BINDING_VALUE_RADIANCE_MAX) buffer RadianceMax { uint radianceMaxBits; };
uniform float uShadowBias;  // light-map texels
uniform vec3 uGridOrigin;   // lights and light maps are in world space: position = offset + this
#endif
in vec3 vPosition;
in vec3 vNormal;
in vec2 vTexUv;
flat in int vTriangle;
uniform mat4 uModel;  // object → offset from the grid's origin
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
#ifdef VALUE_RADIANCE
  vec3 a = corner(3 * vTriangle), b = corner(3 * vTriangle + 1), c = corner(3 * vTriangle + 2);
  vec3 ng = cross(b - a, c - a);
  vec3 sn = dot(n, n) > 0.0f ? normalize(n) : vec3(0.0f);  // vNormal may be an unnormalised face normal
  ng = dot(ng, ng) > 0.0f ? normalize(ng) : sn;
  vec3 L = vec3(0.0f);
  const vec3 pw = p + uGridOrigin;
  for (int i = 0; i < uLightCount; ++i) {
    LightSample ls = sampleDeltaLight(lights[i], pw);
    if (ls.radiance.x + ls.radiance.y + ls.radiance.z <= 0.0f) continue;
    vec3 g = dot(ls.wi, ng) < 0.0f ? -ng : ng;  // the side facing the light
    vec3 s = dot(sn, g) < 0.0f ? -sn : sn;
    float cosI = dot(ls.wi, s);
    if (cosI <= 0.0f || dot(ls.wi, g) <= 0.0f) continue;
    if (lightMapLit(i, pw, s, g, cosI, uShadowBias, 0.0f)) L += albedo * INV_PI * ls.radiance * cosI;
  }
  outRadiance = vec4(L, 1.0f);
  atomicMax(radianceMaxBits, floatBitsToUint(max(max(L.x, L.y), L.z)));
#endif
}
