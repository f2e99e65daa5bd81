// reference_gl integrator=path|direct|nearfield (illum/methods/reference_gl.cpp):
// the estimators of `reference` (illum/methods/reference.cpp: pathLi,
// nearFieldLi, directLight, emissionWeight) on the GL device, through the
// scene's triangles in the BVH — a second implementation of the same
// integrals, tested against the first statistically (block means):
//   path       next-event estimation for the delta lights and one point of
//              the area lights per vertex (chosen by power, uniform on its
//              triangle), BRDF sampling for the environment and, weighted by
//              the power heuristic (Veach 1997, §9.2), the emitters; Russian
//              roulette after pass.rrDepth bounces; "direct" is the light that
//              reaches the first vertex along one segment, "indirect" the rest
//   direct     path with pass.maxDepth = 1
//   nearfield  (REFERENCE_NEARFIELD) direct light at the visible point plus
//              one bounce to a surface within pass.radius, whose exact direct
//              light is the indirect part; rays that leave the radius read the
//              environment when pass.env is set
// pass.glossy (GLOSSY_*): the surfaces that reflect by their Phong lobe, as the reference's glossy.
// Materials, textures and delta lights come from the GPU scene
// (shared/gpu_scene.glsl; the first pass.deltaLights entries of `lights` are the
// scene's own, the rest the framework's per-sample emitter spots, not read
// here), area lights from gpu_emitters (shared/emitters.glsl).
#include "exact.glsl"
#include "shared/brdf.glsl"
#include "shared/emitters.glsl"
#include "shared/environment.glsl"
#include "shared/gpu_scene.glsl"
layout(std430, binding = BINDING_EMITTERS) readonly buffer EmitterBuffer { PackedEmitter emitters[]; };
layout(std430, binding = BINDING_EMITTER_OF) readonly buffer EmitterOfBuffer { int emitterOf[]; };
layout(std430, binding = BINDING_SCENE_VERTICES) readonly buffer SceneVertices { float sceneVertices[]; };

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = IMAGE_SAMPLE) uniform image2D uImage;
layout(rgba32f, binding = IMAGE_SAMPLE_AOV0) uniform writeonly image2D uIndirectAov;
layout(rgba32f, binding = IMAGE_SAMPLE_AOV1) uniform writeonly image2D uDirectAov;

struct Surface {
  vec3 p, ng, n;  // ng and n face the incoming ray
  vec3 wo;
  float t;  // distance from the ray's origin
  BrdfParams brdf;
  vec3 emission;  // Le towards wo (0 behind a one-sided emitter)
  int emitter;    // index in `emitters`, or −1
};

vec2 cornerUv(uint corner) {
  const uint i = corner * SCENE_VERTEX_FLOATS + SCENE_VERTEX_UV;
  return vec2(sceneVertices[i], sceneVertices[i + 1u]);
}

vec3 emitterLe(int e, vec3 w) {
  return emitterRadianceToward(emitters[e].normalSides.xyz, emitters[e].radiance.xyz,
                               emitters[e].normalSides.w > 0.5f, w);
}

// The density (per unit area) of the emitter points directLight draws on emitter e.
float emitterPdfArea(int e) { return (emitters[e].p0Cdf.w - emitters[e].e1CdfLo.w) / emitters[e].e2Area.w; }

bool intersectScene(vec3 o, vec3 d, float tmax, out Surface sp) {
  const BvhHit h = traceBvh(o, d, tmax, false);
  if (h.hit == 0u) return false;
  const uint t = h.triangle;
  sp.p = o + h.t * d;
  sp.t = h.t;
  sp.wo = -d;
  sp.emitter = emitterOf[t];
  sp.emission = sp.emitter >= 0 ? emitterLe(sp.emitter, sp.wo) : vec3(0.0f);
  const SurfaceNormals s = hitNormals(h, sp.wo);
  sp.n = s.n;
  sp.ng = s.ng;
  const int m = triMaterial[t];
  vec3 albedo = materials[m].albedoLayer.xyz;
  const float layer = materials[m].albedoLayer.w;
  if (layer >= 0.0f) {
    const vec2 uv =
        (1.0f - h.u - h.v) * cornerUv(3u * t) + h.u * cornerUv(3u * t + 1u) + h.v * cornerUv(3u * t + 2u);
    albedo *= textureLod(albedoTextures, vec3(uv.x, 1.0f - uv.y, layer), 0.0f).xyz;
  }
  sp.brdf = gpuMaterialBrdf(m, albedo);
  return true;
}

vec3 leaving(Surface sp, vec3 dir) { return offsetOffSurface(sp.p, sp.ng, dir, pass.eps); }

// Delta lights + one area-light point by NEE; `followed`: a BRDF sample
// follows this vertex (then the NEE share is MIS-weighted, else it is 1).
vec3 directLight(Surface sp, inout uint rng, bool followed) {
  vec3 sum = vec3(0.0f);
  for (int i = 0; i < pass.deltaLights; ++i) {
    const PackedLight L = lights[i];
    const LightSample ls = sampleDeltaLight(L, sp.p);
    if (ls.radiance == vec3(0.0f) || dot(ls.wi, sp.n) <= 0.0f || dot(ls.wi, sp.ng) <= 0.0f) continue;
    const vec3 f = evalBrdf(sp.brdf, sp.n, sp.wo, ls.wi);
    if (f == vec3(0.0f)) continue;
    const vec3 o = leaving(sp, ls.wi);
    const float tfar = ls.dist >= 1e29f ? 1e30f : length(L.positionType.xyz - o) * (1.0f - 1e-5f);
    if (occluded(o, ls.wi, tfar)) continue;
    sum += f * ls.radiance * dot(ls.wi, sp.n);
  }
  if (pass.emitterCount == 0 || (followed && pass.emitterSampling == EMITTER_SAMPLING_BRDF)) return sum;
  vec2 u;
  u.x = rngNext(rng);
  u.y = rngNext(rng);
  // The emitter: the first whose CDF reaches u.x (by power), then a point uniform on it.
  int lo = 0, hi = pass.emitterCount;
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    if (emitters[mid].p0Cdf.w < u.x)
      lo = mid + 1;
    else
      hi = mid;
  }
  const int e = min(lo, pass.emitterCount - 1);
  const float cdfLo = emitters[e].e1CdfLo.w, width = emitters[e].p0Cdf.w - cdfLo;
  const vec3 ep = uniformTrianglePoint(emitters[e].p0Cdf.xyz, emitters[e].e1CdfLo.xyz, emitters[e].e2Area.xyz,
                                       emitterRescale(u.x, cdfLo, width), u.y);
  const vec3 d = ep - sp.p;
  const float dist2 = dot(d, d);
  if (!(dist2 > 0.0f)) return sum;
  const vec3 wi = d / sqrt(dist2);
  const float cosS = dot(wi, sp.n), cosL = abs(dot(emitters[e].normalSides.xyz, wi));
  if (cosS <= 0.0f || dot(wi, sp.ng) <= 0.0f || !(cosL > 0.0f)) return sum;
  const vec3 Le = emitterLe(e, -wi);
  if (Le == vec3(0.0f)) return sum;
  const vec3 f = evalBrdf(sp.brdf, sp.n, sp.wo, wi);
  if (f == vec3(0.0f)) return sum;
  // The shadow ray runs to the point itself (see the reference's directLight).
  const vec3 o = leaving(sp, wi), toPoint = ep - o;
  const float len = length(toPoint);
  if (occluded(o, toPoint / len, len * (1.0f - 1e-4f))) return sum;
  const float pdfLight = (width / emitters[e].e2Area.w) * dist2 / cosL;  // solid angle
  float w = 1.0f;
  if (followed && pass.emitterSampling == EMITTER_SAMPLING_MIS) {
    const float pdfBrdf = brdfPdf(sp.brdf, sp.n, sp.wo, wi);
    w = powerHeuristic(pdfLight, pdfBrdf);
  }
  return sum + f * Le * (cosS * w / pdfLight);
}

// The weight of emission met by a BRDF sample of density pdfBrdf (solid angle).
float emissionWeight(Surface hit, float pdfBrdf) {
  if (hit.emitter < 0 || pass.emitterSampling == EMITTER_SAMPLING_BRDF) return 1.0f;
  if (pass.emitterSampling == EMITTER_SAMPLING_LIGHT) return 0.0f;
  const float cosL = abs(dot(emitters[hit.emitter].normalSides.xyz, hit.wo));
  if (!(cosL > 0.0f)) return 0.0f;
  const float pdfLight = emitterPdfArea(hit.emitter) * hit.t * hit.t / cosL;
  return powerHeuristic(pdfBrdf, pdfLight);
}

vec3 rng3(inout uint rng) {
  vec3 u;
  u.x = rngNext(rng);
  u.y = rngNext(rng);
  u.z = rngNext(rng);
  return u;
}

vec3 pathLi(vec3 o, vec3 d, inout uint rng, inout vec3 indirect) {
  vec3 L = vec3(0.0f), beta = vec3(1.0f);
  vec3 betaSegment = vec3(1.0f);  // the direct channel's terms met at depth 1 (see the reference's pathLi)
  float pdfBrdf = 0.0f;           // of the direction that led to this vertex (none for the camera ray)
  for (int depth = 0;; ++depth) {
    Surface sp;
    if (!intersectScene(o, d, 1e30f, sp)) {
      // The camera sees the environment as background always; as a light only with pass.env.
      if (depth == 0 || pass.env != 0) {
        const bool isIndirect = depth >= 2 || (depth == 1 && pass.envIndirect != 0);
        const vec3 e = (depth == 1 && !isIndirect ? betaSegment : beta) * gpuEnvironmentRadiance(d);
        L += e;
        if (isIndirect) indirect += e;
      }
      break;
    }
    if (depth >= 1 && pass.glossy != GLOSSY_ALL) sp.brdf.ks = vec3(0.0f);  // bounce surfaces: diffuse
    if (sp.emission != vec3(0.0f)) {
      const vec3 e =
          (depth == 1 ? betaSegment : beta) * sp.emission * (depth == 0 ? 1.0f : emissionWeight(sp, pdfBrdf));
      L += e;
      if (depth >= 2) indirect += e;
    }
    if (depth == pass.maxDepth) break;
    const vec3 nee = beta * directLight(sp, rng, true);
    L += nee;
    if (depth >= 1) indirect += nee;
    const vec3 wi = sampleBrdf(sp.brdf, sp.n, sp.wo, rng3(rng));
    const float pdf = brdfPdf(sp.brdf, sp.n, sp.wo, wi);
    if (!(pdf > 0.0f) || dot(wi, sp.n) <= 0.0f || dot(wi, sp.ng) <= 0.0f) break;
    const float cosPdf = dot(wi, sp.n) / pdf;
    betaSegment = beta * evalBrdf(sp.brdf, sp.n, sp.wo, wi) * cosPdf;
    beta = depth == 0 && pass.glossy == GLOSSY_DIRECT
               ? beta * evalBrdf(diffusePart(sp.brdf), sp.n, sp.wo, wi) * cosPdf
               : betaSegment;
    pdfBrdf = pdf;
    if (depth + 1 >= pass.rrDepth) {
      const float q = russianRouletteQ(betaSegment);
      if (rngNext(rng) < q) break;
      beta /= 1.0f - q;
      betaSegment /= 1.0f - q;
    }
    o = leaving(sp, wi);
    d = wi;
  }
  return L;
}

vec3 nearFieldLi(vec3 o, vec3 d, inout uint rng, inout vec3 indirect) {
  Surface x;
  if (!intersectScene(o, d, 1e30f, x)) return gpuEnvironmentRadiance(d);
  vec3 L = x.emission + directLight(x, rng, true);
  const vec3 wi = sampleBrdf(x.brdf, x.n, x.wo, rng3(rng));
  const float pdf = brdfPdf(x.brdf, x.n, x.wo, wi);
  if (!(pdf > 0.0f) || dot(wi, x.n) <= 0.0f || dot(wi, x.ng) <= 0.0f) return L;
  const vec3 weight = evalBrdf(x.brdf, x.n, x.wo, wi) * (dot(wi, x.n) / pdf);
  const vec3 weightIndirect = pass.glossy == GLOSSY_DIRECT
                                  ? evalBrdf(diffusePart(x.brdf), x.n, x.wo, wi) * (dot(wi, x.n) / pdf)
                                  : weight;
  // The bounce surface y: its emission is direct light at x (the MIS share),
  // its direct light the one indirect bounce.
  Surface y;
  if (intersectScene(leaving(x, wi), wi, pass.radius, y)) {
    if (y.emission != vec3(0.0f)) L += weight * y.emission * emissionWeight(y, pdf);
    if (pass.glossy != GLOSSY_ALL) y.brdf.ks = vec3(0.0f);
    indirect = weightIndirect * directLight(y, rng, false);
  } else if (pass.env != 0) {
    indirect = weightIndirect * gpuEnvironmentRadiance(wi);
  }
  return L + indirect;
}

void main() {
  ivec2 q;
  uint state;
  vec3 dir;
  if (!pixelRay(imageSize(uImage), q, state, dir)) return;
  vec3 indirect = vec3(0.0f);
#ifdef REFERENCE_NEARFIELD
  const vec3 L = nearFieldLi(primaryOrigin(dir), dir, state, indirect);
#else
  const vec3 L = pathLi(primaryOrigin(dir), dir, state, indirect);
#endif
  imageStore(uImage, q, vec4(L, 1.0f));
  if (pass.writeIndirect != 0) imageStore(uIndirectAov, q, vec4(indirect, 1.0f));
  if (pass.writeDirect != 0) imageStore(uDirectAov, q, vec4(L - indirect, 1.0f));
}
