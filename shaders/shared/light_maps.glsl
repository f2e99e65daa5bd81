// Light maps: one set of faces per delta light, all layers of one 2D array
// texture per channel — six perspective faces for a point light (or a spot
// light wider than 60°), one perspective face for a narrower spot light, one
// orthographic face fitted to the scene for a directional light. Each texel
// stores the distance to the light (shadow maps, the `direct` module) and, for
// reflective shadow maps (Dachsbacher and Stamminger 2005; VGI §5.1), the world
// position, the normal and the diffusely reflected direct radiance of the
// surface the light sees there.
//
// Distances are measured like the shadow test needs them: from the light
// position (perspective faces) or along the light's direction of travel from
// the map's plane (orthographic faces).
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif

#include "bindings.glsl"
#include "brdf.glsl"
#include "gpu_scene.glsl"

SHARED_BEGIN

struct LightFace {
  mat4 viewProj;
  mat4 rayUnproject;    // NDC (x, y, −1) → a point on the texel's ray (perspective: 1 unit from the eye; ortho: the near plane)
  vec4 eyeOrtho;        // xyz eye (light position, or the plane origin); w = 1 for orthographic
  vec4 axisTexel;       // xyz view axis; w = texel size per unit distance (perspective) or in world units
};

// The cube face (GL order +x −x +y −y +z −z) a direction falls in.
SHARED_FN int cubeFaceIndex(vec3 d) {
  vec3 a = abs(d);
  if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0f ? 0 : 1;
  if (a.y >= a.z) return d.y >= 0.0f ? 2 : 3;
  return d.z >= 0.0f ? 4 : 5;
}

SHARED_FN vec3 lightFaceEye(SHARED_IN(LightFace) f) { return vec3(f.eyeOrtho.x, f.eyeOrtho.y, f.eyeOrtho.z); }

// The face of a light (first, count) that sees point p.
SHARED_FN int lightMapFace(SHARED_IN(LightFace) first, int firstIndex, int count, vec3 p) {
  return count == 6 ? firstIndex + cubeFaceIndex(p - lightFaceEye(first)) : firstIndex;
}

// The distance the map stores for a surface at p.
SHARED_FN float lightMapDistance(SHARED_IN(LightFace) f, vec3 p) {
  vec3 d = p - lightFaceEye(f);
  if (f.eyeOrtho.w > 0.5f) return dot(d, vec3(f.axisTexel.x, f.axisTexel.y, f.axisTexel.z));
  return length(d);
}

// The world size of one texel at a stored distance.
SHARED_FN float lightMapTexelWorld(SHARED_IN(LightFace) f, float dist) {
  return f.eyeOrtho.w > 0.5f ? f.axisTexel.w : f.axisTexel.w * dist;
}

// Texture coordinates of p in the face ([0,1]² inside).
SHARED_FN vec2 lightMapUv(SHARED_IN(LightFace) f, vec3 p) {
  vec4 c = f.viewProj * vec4(p.x, p.y, p.z, 1.0f);
  return vec2(c.x / c.w * 0.5f + 0.5f, c.y / c.w * 0.5f + 0.5f);
}

// The centre of the texel of an n×n map that uv falls in (GL_NEAREST's texel).
SHARED_FN vec2 lightMapTexelCentre(vec2 uv, float n) {
  return vec2((floor(uv.x * n) + 0.5f) / n, (floor(uv.y * n) + 0.5f) / n);
}

// What the map would store at texel centre uvCentre if the plane through q
// with normal ng were the surface there: the map's distance (as
// lightMapDistance) to where the ray through that texel centre meets the
// plane — exactly what rasterising that plane writes, since fragments are
// evaluated at texel centres. Negative when the ray runs within ~0.6° of the
// plane (no stable answer) or meets it behind the light.
SHARED_FN float lightMapPlaneDistance(SHARED_IN(LightFace) f, vec2 uvCentre, vec3 q, vec3 ng) {
  bool ortho = f.eyeOrtho.w > 0.5f;
  // Orthographic: from the texel centre on the near plane along the axis;
  // perspective: from the light through the texel centre.
  vec4 a = f.rayUnproject * vec4(uvCentre.x * 2.0f - 1.0f, uvCentre.y * 2.0f - 1.0f, -1.0f, 1.0f);
  vec3 onRay = vec3(a.x, a.y, a.z) / a.w;
  vec3 o = ortho ? onRay : lightFaceEye(f);
  vec3 d = ortho ? vec3(f.axisTexel.x, f.axisTexel.y, f.axisTexel.z) : normalize(onRay - o);
  float c = dot(d, ng);
  if (abs(c) < 0.01f) return -1.0f;
  float t = dot(q - o, ng) / c;
  if (!ortho && t <= 0.0f) return -1.0f;
  return lightMapDistance(f, o + d * t);
}

// The area a texel covers on the surface it sees at p (geometric normal ng):
// what a texel stands for as a virtual point light (its reflected radiance ×
// this area × cos is the VPL's intensity; Dachsbacher and Stamminger 2005).
// Perspective faces: the texel's solid angle, texel² · cos³ of its angle to
// the face axis (texel per unit distance), times dist² / cos α; orthographic
// faces: texel² / cos α. α is the angle between ng and the light's ray,
// |cos α| clamped at 0.05 (a grazing texel stands for a long strip, which
// is finite on a real surface).
SHARED_FN float lightMapTexelArea(SHARED_IN(LightFace) f, vec3 p, vec3 ng) {
  vec3 axis = vec3(f.axisTexel.x, f.axisTexel.y, f.axisTexel.z);
  float w = f.axisTexel.w;
  if (f.eyeOrtho.w > 0.5f) return w * w / max(abs(dot(ng, axis)), 0.05f);
  vec3 d = p - lightFaceEye(f);
  float dist2 = dot(d, d);
  vec3 dir = d / sqrt(dist2);
  float c = dot(dir, axis);
  return w * w * c * c * c * dist2 / max(abs(dot(ng, dir)), 0.05f);
}

// VGI §5.1: a hit point y back-projected into a reflective shadow map receives
// the stored radiance when |y − p_rsm| < ε, ε = max(v, s/cos α · z/z_near):
// v the voxel discretisation (here the voxel diagonal, as a voxel-entry hit can
// be that far from the surface in its voxel), s/cos α · z/z_near the world size
// of the RSM texel at the stored surface, stretched by the angle α between the
// surface normal and the light direction (cos α clamped at 0.1).
SHARED_FN float backProjectionEpsilon(float voxelDiagonal, float texelWorld, float cosAlpha) {
  return max(voxelDiagonal, texelWorld / max(cosAlpha, 0.1f));
}

SHARED_END

#ifndef __cplusplus
layout(std430, binding = BINDING_LIGHT_FACES) readonly buffer LightFaceBuffer { LightFace lightFaces[]; };
layout(std430, binding = BINDING_LIGHT_RANGES) readonly buffer LightRangeBuffer { ivec4 lightRanges[]; };
layout(binding = TEXUNIT_LIGHT_DISTANCE) uniform sampler2DArray lightDistance;
layout(binding = TEXUNIT_LIGHT_POSITION) uniform sampler2DArray lightPosition;
layout(binding = TEXUNIT_LIGHT_NORMAL) uniform sampler2DArray lightNormal;
layout(binding = TEXUNIT_LIGHT_RADIANCE) uniform sampler2DArray lightRadiance;

// The number of light-map faces: the last light's range ends there (the lights' ranges are
// consecutive, layoutLightFaces).
int lightFaceCount() {
  if (uLightCount <= 0) return 0;
  ivec4 r = lightRanges[uLightCount - 1];
  return r.x + r.y;
}

// The face of light `light` that sees p.
int lightFaceOf(int light, vec3 p) {
  ivec4 r = lightRanges[light];
  return lightMapFace(lightFaces[r.x], r.x, r.y, p);
}

// Shadow test of a surface point p (shading normal n, cos θ to the light;
// geometric normal ng) against the light's distance map. The lookup is moved
// `normalOffset` texels along n. The receiver's distance is taken where the
// stored one was: at the texel's centre, on the receiver's plane
// (lightMapPlaneDistance) — so a plane never shadows itself at any angle
// (no acne at grazing light) and `bias` (texels) only absorbs rounding and
// the neighbour surface of a concave corner, without the large slope-scaled
// bias that lets light leak under thin occluders. Within ~0.6° of grazing it
// falls back to p's own distance with a bias slope-scaled by 1/cos θ (≤ 5×).
bool lightMapLit(int light, vec3 p, vec3 n, vec3 ng, float cosI, float bias, float normalOffset) {
  LightFace face = lightFaces[lightFaceOf(light, p)];
  float texel = lightMapTexelWorld(face, lightMapDistance(face, p));
  vec3 q = p + n * (normalOffset * texel);
  int f = lightFaceOf(light, q);
  face = lightFaces[f];
  vec2 uv = lightMapUv(face, q);
  float stored = texture(lightDistance, vec3(uv, float(f))).x;
  float own = lightMapDistance(face, q);
  float onPlane = lightMapPlaneDistance(face, lightMapTexelCentre(uv, float(textureSize(lightDistance, 0).x)), q, ng);
  // Past q the plane is trusted for one texel only: at grazing light the
  // texel centre's ray meets it up to texel / cos θ away, beyond where the
  // face may end (a box's foot: the floor in front of that point would shadow
  // it). Taking the nearer never shadows a plane by itself.
  if (onPlane >= 0.0f) return min(onPlane, own + texel) - bias * texel <= stored;
  return own - bias * texel / max(cosI, 0.2f) <= stored;
}

// The light of every delta light reflected at p toward wo by `brdf`
// (shading normal n, geometric normal ng), shadowed through the light maps
// (lightMapLit with `bias` and `normalOffset` in texels): the deferred direct
// pass, and voxelpath's glossy lobe at path vertices.
vec3 lightMapsDirect(BrdfParams brdf, vec3 p, vec3 n, vec3 ng, vec3 wo, float bias, float normalOffset) {
  vec3 sum = vec3(0.0f);
  for (int i = 0; i < uLightCount; ++i) {
    LightSample ls = sampleDeltaLight(lights[i], p);
    float cosI = dot(ls.wi, n);
    bool lit = cosI > 0.0f && (ls.radiance.x + ls.radiance.y + ls.radiance.z) > 0.0f;
    if (lit) lit = lightMapLit(i, p, n, ng, cosI, bias, normalOffset);
    if (lit) sum += evalBrdf(brdf, n, wo, ls.wi) * ls.radiance * cosI;
  }
  return sum;
}

// lightMapsDirect on both sides of a surface at once — front along n, back along −n (the same
// values as the two calls: a light reaches at most one side, so each light takes one sample and
// one shadow test, on the side it lights; wo is each side's own normal).
struct TwoSided {
  vec3 front, back;
};
TwoSided lightMapsDirectTwoSided(BrdfParams brdf, vec3 p, vec3 n, float bias, float normalOffset) {
  TwoSided r;
  r.front = vec3(0.0f);
  r.back = vec3(0.0f);
  for (int i = 0; i < uLightCount; ++i) {
    LightSample ls = sampleDeltaLight(lights[i], p);
    float c = dot(ls.wi, n);
    vec3 side = c > 0.0f ? n : -n;
    float cosI = dot(ls.wi, side);
    bool lit = cosI > 0.0f && (ls.radiance.x + ls.radiance.y + ls.radiance.z) > 0.0f;
    if (lit) lit = lightMapLit(i, p, side, side, cosI, bias, normalOffset);
    if (!lit) continue;
    vec3 L = evalBrdf(brdf, side, side, ls.wi) * ls.radiance * cosI;
    if (c > 0.0f)
      r.front += L;
    else
      r.back += L;
  }
  return r;
}

// --- Reading reflective shadow maps (VGI §5.1): back-projection of a point
// into every light's RSM, and RSM texels as virtual point lights.

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
  int res = textureSize(lightPosition, 0).x;
  RsmTexel r;
  r.face = lightFaceOf(l, y);
  vec2 uv = lightMapUv(lightFaces[r.face], y);
  r.texel = ivec3(min(ivec2(uv * float(res)), ivec2(res - 1)), r.face);
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
// entered at distance t, read back from every RSM (diffusely reflected: what
// the RSMs store). voxelDiagonal: the hit's uncertainty (the voxel tracers':
// the voxel diagonal); maxT: how far the ray was traced (r); refine:
//   false, VGI §5.1: the voxel entry y = o + t·d is back-projected and
//     takes the texel's radiance when |y − p_rsm| < ε (ε ≥ the voxel diagonal,
//     as y lies up to a diagonal off the surface).
//   true: the texel y projects to says which surface the light sees
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
  bool seenThrough;  // a light sees past y and none lights it: nothing is there
};
BackProjection rsmBackProject(vec3 o, vec3 d, float t, float voxelDiagonal, float maxT, bool refine) {
  precise vec3 y = o + t * d;
  vec3 sum = vec3(0.0f);
  bool through = false;
  for (int l = 0; l < uLightCount; ++l) {
    RsmTexel r = rsmTexelAt(l, y);
    if (r.face < 0) {
      through = through || texelFetch(lightPosition, r.texel, 0).w == 0.0f && insideLightMap(l, y);
      continue;
    }
    LightFace face = lightFaces[r.face];
    through = through || lightMapDistance(face, r.position) > lightMapDistance(face, y) + 1.5f * voxelDiagonal;
    if (!refine) {
      if (distance(y, r.position) < rsmEpsilon(l, r, voxelDiagonal)) sum += texelFetch(lightRadiance, r.texel, 0).xyz;
      continue;
    }
    // Up to three steps: a step that lands on another surface's texel
    // (small features: the first texel belongs to a neighbour) tries that one.
    for (int step = 0; step < 3; ++step) {
      float c = dot(d, r.normal);
      if (c >= -1e-4f) break;  // parallel to the plane, or meeting its unlit side
      precise float ts = dot(r.position - o, r.normal) / c;
      if (ts < t - voxelDiagonal || ts > t + 8.0f * voxelDiagonal || ts > maxT) break;
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

// An RSM texel as a virtual point light (Dachsbacher and Stamminger 2005):
// the surface the light saw there, its diffusely reflected radiance, and the
// area it stands for (lightMapTexelArea); the VPL's intensity toward ω is
// radiance · area · max(0, n·ω). valid is false where the light saw nothing.
struct RsmVpl {
  vec3 position, normal, radiance;
  float area;
  bool valid;
};
RsmVpl rsmTexelVpl(int face, ivec2 texel) {
  RsmVpl v;
  vec4 P = texelFetch(lightPosition, ivec3(texel, face), 0);
  v.valid = P.w != 0.0f;
  v.position = P.xyz;
  v.normal = texelFetch(lightNormal, ivec3(texel, face), 0).xyz;
  v.radiance = v.valid ? texelFetch(lightRadiance, ivec3(texel, face), 0).xyz : vec3(0.0f);
  v.area = v.valid ? lightMapTexelArea(lightFaces[face], v.position, v.normal) : 0.0f;
  return v;
}
#endif
