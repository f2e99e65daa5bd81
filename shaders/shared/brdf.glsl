// BRDF: Lambert plus a normalised Phong lobe (Lafortune & Willems 1994):
//   f(wo, wi) = albedo/π + ks (e+2)/(2π) max(0, r·wi)^e,   r = reflect(−wo, n).
// Energy-conserving when albedo + ks ≤ 1. Sampling is a lobe mixture chosen by
// the lobes' mean reflectance; pdf is the mixture's.
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
#include "constants.glsl"
#include "sampling.glsl"
SHARED_BEGIN

struct BrdfParams {
  vec3 albedo;
  vec3 ks;
  float exponent;
};

// The Lambert lobe alone (the Phong lobe's ks zero): what a model that reflects diffusely sees.
SHARED_FN BrdfParams diffusePart(BrdfParams m) {
  BrdfParams d = m;
  d.ks = vec3(0.0f);
  return d;
}

SHARED_FN vec3 reflectAbout(vec3 wo, vec3 n) { return 2.0f * dot(n, wo) * n - wo; }

// f(wo, wi); both directions point away from the surface; zero below the horizon.
SHARED_FN vec3 evalBrdf(BrdfParams m, vec3 n, vec3 wo, vec3 wi) {
  float ci = dot(n, wi);
  float co = dot(n, wo);
  if (ci <= 0.0f || co <= 0.0f) return vec3(0.0f);
  vec3 f = m.albedo * INV_PI;
  if (m.ks.x + m.ks.y + m.ks.z > 0.0f) {
    float c = max(dot(reflectAbout(wo, n), wi), 0.0f);
    f = f + m.ks * ((m.exponent + 2.0f) * INV_2PI * pow(c, m.exponent));
  }
  return f;
}

SHARED_FN float specularLobeProbability(BrdfParams m) {
  float d = m.albedo.x + m.albedo.y + m.albedo.z;
  float s = m.ks.x + m.ks.y + m.ks.z;
  return d + s > 0.0f ? s / (d + s) : 0.0f;
}

SHARED_FN float brdfPdf(BrdfParams m, vec3 n, vec3 wo, vec3 wi) {
  float ci = dot(n, wi);
  if (ci <= 0.0f) return 0.0f;
  float ps = specularLobeProbability(m);
  float pdf = (1.0f - ps) * ci * INV_PI;
  if (ps > 0.0f) {
    float c = max(dot(reflectAbout(wo, n), wi), 0.0f);
    pdf = pdf + ps * (m.exponent + 1.0f) * INV_2PI * pow(c, m.exponent);
  }
  return pdf;
}

// u.z picks the lobe, u.xy place the direction. The result may lie below the
// surface (specular lobe near grazing); callers treat that as zero weight.
SHARED_FN vec3 sampleBrdf(BrdfParams m, vec3 n, vec3 wo, vec3 u) {
  if (u.z < specularLobeProbability(m)) {
    Basis f = makeBasis(reflectAbout(wo, n));
    return basisToWorld(f, samplePowerCosine(vec2(u.x, u.y), m.exponent));
  }
  Basis f = makeBasis(n);
  return basisToWorld(f, cosineSampleHemisphere(vec2(u.x, u.y)));
}

SHARED_END
