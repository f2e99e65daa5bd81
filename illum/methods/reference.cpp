// Exact reference renderer: CPU path tracing on Embree, with the exact
// counterparts of the approximate GL modules' integrals.
//
//   path       full global illumination (pbrt-style: next-event estimation for
//              the delta lights and the area lights, BRDF sampling for the
//              environment and, MIS-weighted, the emitters; Russian roulette
//              after `rr_depth` bounces)
//   direct     the path integrator with maxdepth 1: emission + delta and area
//              lights with exact visibility (+ environment via one BRDF sample)
//   nearfield  direct light at the visible point plus exactly one indirect
//              bounce gathered from surfaces within distance `radius`; their
//              outgoing radiance is their exact direct light; rays
//              that hit nothing within `radius` read the environment (`env`) —
//              the exact counterpart of VGI §5.1 (Thiedemann et al. 2011)
//   ao         ambient occlusion: fraction of cosine-weighted rays that travel
//              `radius` unoccluded (camera misses are 0)
//
// glossy (path, nearfield): the surfaces that reflect by their Phong lobe — all; first (bounce
// surfaces reflect diffusely); direct (also the indirect light the visible surface reflects goes
// through its diffuse lobe alone; its direction is still drawn from the whole BRDF, so the direct
// light and its MIS are glossy=all's). The omissions of a method's model, so that its
// model-matched counterpart (MethodInfo::counterpart) leaves out what the method leaves out.
//
// Area lights (emissive meshes, core/emitters.h) are sampled by next-event
// estimation and by the BRDF, combined by multiple importance sampling with
// the power heuristic (Veach 1997, §9.2; `emitter_sampling=mis`); `light` and
// `brdf` keep one strategy each (a noisier estimator of the same integral:
// what the MIS tests compare against). An emitter met by a nearfield bounce
// ray is direct light (its MIS share goes to `direct`); the bounce's own direct
// light is estimated by NEE alone, since no BRDF sample follows it.
//
// Determinism: every (pixel, sample) owns a PCG32 stream seeded from (seed,
// pixel, sample), and the framework's sample loop adds the samples of each
// pixel in order (double sums), so the image is the same for any thread
// count. A sample is one pass over the image (tiles in parallel); Ctrl-C
// drops the sample in flight, so every pixel has the same sample count.
//
// Parameters: `vgi render --help-module reference` (and docs/PARAMETERS.md), generated from the
// ParamSet declarations (this file's and its kits'), whose doc strings are the one place they are written.
//
// path with visibility=voxels does the same for `voxelpath`: every bounce ray
// (not the camera ray) finds its first hit through the voxel grid, from
// `offset` diagonals along the normal, and the surface there exactly; NEE,
// shading and emission stay exact. voxelpath against it is the voxel shading
// (hit point, mean normal and BRDF) and RSM direct-light error; it against
// the exact path tracer the voxel-visibility error.
//
// nearfield with visibility=voxels isolates the voxel-visibility error of the
// `nearfield` module: the bounce ray starts `offset` voxel diagonals along the
// normal (VGI's one diagonal by default; the module starts at ½ and passes
// its own voxels instead) and the hierarchical tracer decides, on an exact
// (triangle–box) voxelization, whether and where it stops within `radius`;
// the surface there is then found and shaded exactly (Embree, within two voxel
// diagonals of the hit voxel's entry; none there — a voxel the ray grazes
// without meeting its surface — contributes nothing).
#include "illum/methods/reference.h"

#include <algorithm>
#include <cmath>

#include "core/emitters.h"
#include "core/error.h"
#include "core/gpu_scene.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "illum/framework/sample_loop.h"
#include "illum/kits/exact_params.h"
#include "illum/resources/bvh.h"
#include "illum/resources/or_mip_pyramid.h"
#include "shaders/shared/brdf.glsl"
#include "shaders/shared/exact_surface.glsl"
#include "shaders/shared/lights.glsl"
#include "shaders/shared/sampling.glsl"
#include "traverse/embree_tracer.h"
#include "traverse/or_mip_pyramid.h"
#include "traverse/ray_tracers.h"

namespace vgi {

namespace {

using namespace vgi::shared;

// O'Neill's PCG32 (XSH RR), one stream per (pixel, sample).
struct Pcg32 {
  uint64_t state = 0, inc = 1;
  Pcg32(uint64_t seed, uint64_t stream) {
    inc = (stream << 1u) | 1u;
    next();
    state += seed;
    next();
  }
  uint32_t next() {
    uint64_t old = state;
    state = old * 6364136223846793005ULL + inc;
    uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = uint32_t(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }
  float uniform() { return uintToUnitFloat(next()); }
  vec2 uniform2() {
    float a = uniform();
    return vec2(a, uniform());
  }
  vec3 uniform3() {
    vec2 a = uniform2();
    return vec3(a.x, a.y, uniform());
  }
};

struct SurfacePoint {
  vec3 p, ng, n;  // ng and n face the incoming ray
  vec3 wo;
  float t = 0;  // distance from the ray's origin
  BrdfParams brdf;
  vec3 emission;     // Le towards wo (0 behind a one-sided emitter)
  int emitter = -1;  // index in Emitters, or −1
};

class ReferenceRenderer : public Method {
 public:
  ReferenceRenderer(ParamSet& params, const Scene& scene)
      : p_(readExactParams(params, scene, "reference", true)) {}

  SceneNeeds needs() const override {
    SceneNeeds n;
    n.add(BvhNeed{});
    if (p_.voxelVisibility) {
      BinaryGridNeed grid;
      grid.resolution = p_.voxels;
      grid.voxelizer = "exact";
      n.add(OrMipPyramidNeed{grid});
    }
    return n;
  }
  void prepareFrame(Frame& f) override;
  bool addSample(Frame& f, int k) override;
  void finishFrame(Frame& f) override;
  // nearfield splits its estimate into the direct part and the one indirect
  // bounce, path into the light reaching the first vertex along one segment
  // and the rest.
  std::vector<std::string> outputs() const override {
    return p_.splitsDirectIndirect() ? std::vector<std::string>{"direct", "indirect"}
                                     : std::vector<std::string>{};
  }

 private:
  // Radiance along (o, d); `indirect` receives the indirect part where the integrator separates one.
  vec3 li(vec3 o, vec3 d, Pcg32& rng, vec3& indirect) const;
  vec3 pathLi(vec3 o, vec3 d, Pcg32& rng, vec3& indirect) const;
  vec3 nearFieldLi(vec3 o, vec3 d, Pcg32& rng, vec3& indirect) const;
  float aoLi(vec3 o, vec3 d, Pcg32& rng) const;
  bool intersect(vec3 o, vec3 d, float tmax, SurfacePoint& sp) const;
  // Delta lights + area lights by NEE; `followed`: a BRDF sample follows this
  // vertex (then the NEE share is weighted by p_.emitterSampling, else it is 1).
  vec3 directLight(const SurfacePoint& sp, Pcg32& rng, bool followed) const;
  // The weight of emission met by a BRDF sample of density `pdfBrdf` (solid angle).
  float emissionWeight(const SurfacePoint& hit, float pdfBrdf) const;
  vec3 offsetOrigin(const SurfacePoint& sp, vec3 dir) const;

  ExactParams p_;
  float sceneDiagonal_ = 1;

  // Per frame (prepareFrame).
  const Scene* scene_ = nullptr;
  const FlatScene* flat_ = nullptr;
  const EmbreeTracer* tracer_ = nullptr;
  const Emitters* emitters_ = nullptr;
  std::unique_ptr<RayTracer> voxelTracer_;  // visibility=voxels, over the resources' exact pyramid
  float voxelDiagonal_ = 0;
  std::vector<PackedLight> lights_;
  float eps_ = 1e-5f;
  PinholeView view_{};
};

bool ReferenceRenderer::intersect(vec3 o, vec3 d, float tmax, SurfacePoint& sp) const {
  TriangleHit h = tracer_->firstHit(o, d, 0.0f, tmax);
  if (!h.hit) return false;
  const size_t t = size_t(h.triangle);
  const float w = 1.0f - h.u - h.v;
  const vec3* P = &flat_->positions[3 * t];
  const vec3* N = &flat_->normals[3 * t];
  const vec2* UV = &flat_->uvs[3 * t];
  sp.p = o + h.t * d;
  sp.t = h.t;
  sp.wo = -d;
  sp.ng = glm::normalize(glm::cross(P[1] - P[0], P[2] - P[0]));
  sp.emitter = emitters_->emitterOfTriangle(t);
  sp.emission = sp.emitter >= 0 ? emitters_->radianceToward(sp.emitter, sp.wo) : vec3(0.0f);
  const SurfaceNormals normals = orientNormals(sp.ng, w * N[0] + h.u * N[1] + h.v * N[2], sp.wo);
  sp.n = normals.n;
  sp.ng = normals.ng;
  const Material& m = scene_->materials[size_t(flat_->material[t])];
  sp.brdf.albedo = m.albedo;
  if (m.albedoTexture >= 0)
    sp.brdf.albedo *= scene_->textures[size_t(m.albedoTexture)].lookup(w * UV[0] + h.u * UV[1] + h.v * UV[2]);
  sp.brdf.ks = m.ks;
  sp.brdf.exponent = m.exponent;
  return true;
}

vec3 ReferenceRenderer::offsetOrigin(const SurfacePoint& sp, vec3 dir) const {
  return offsetOffSurface(sp.p, sp.ng, dir, eps_);
}

vec3 ReferenceRenderer::directLight(const SurfacePoint& sp, Pcg32& rng, bool followed) const {
  vec3 sum(0.0f);
  for (const PackedLight& L : lights_) {
    LightSample ls = sampleDeltaLight(L, sp.p);
    if (ls.radiance == vec3(0.0f) || dot(ls.wi, sp.n) <= 0.0f || dot(ls.wi, sp.ng) <= 0.0f) continue;
    vec3 f = evalBrdf(sp.brdf, sp.n, sp.wo, ls.wi);
    if (f == vec3(0.0f)) continue;
    vec3 o = offsetOrigin(sp, ls.wi);
    float tfar = ls.dist >= 1e29f ? 1e30f : glm::length(vec3(L.positionType) - o) * (1.0f - 1e-5f);
    if (tracer_->occluded(o, ls.wi, 0.0f, tfar)) continue;
    sum += f * ls.radiance * dot(ls.wi, sp.n);
  }
  if (emitters_->empty() || (followed && p_.emitterSampling == EmitterSampling::Brdf)) return sum;
  // One point of the area lights (chosen by power, uniform on its triangle).
  const EmitterSample es = emitters_->sample(rng.uniform2());
  const vec3 d = es.p - sp.p;
  const float dist2 = dot(d, d);
  if (!(dist2 > 0.0f)) return sum;
  const vec3 wi = d / std::sqrt(dist2);
  const float cosS = dot(wi, sp.n), cosL = std::abs(dot(es.normal, wi));
  if (cosS <= 0.0f || dot(wi, sp.ng) <= 0.0f || !(cosL > 0.0f)) return sum;
  const vec3 Le = emitters_->radianceToward(es.emitter, -wi);
  if (Le == vec3(0.0f)) return sum;
  const vec3 f = evalBrdf(sp.brdf, sp.n, sp.wo, wi);
  if (f == vec3(0.0f)) return sum;
  // The shadow ray runs from the offset origin to the point itself: along wi
  // from there it would meet the emitter's plane before the point, at grazing
  // angles, and count the emitter as its own occluder.
  const vec3 o = offsetOrigin(sp, wi), toPoint = es.p - o;
  const float len = glm::length(toPoint);
  if (tracer_->occluded(o, toPoint / len, 0.0f, len * (1.0f - 1e-4f))) return sum;
  const float pdfLight = es.pdfArea * dist2 / cosL;  // solid angle
  float w = 1.0f;
  if (followed && p_.emitterSampling == EmitterSampling::Mis) {
    const float pdfBrdf = brdfPdf(sp.brdf, sp.n, sp.wo, wi);
    w = powerHeuristic(pdfLight, pdfBrdf);
  }
  return sum + f * Le * (cosS * w / pdfLight);
}

float ReferenceRenderer::emissionWeight(const SurfacePoint& hit, float pdfBrdf) const {
  if (hit.emitter < 0 || p_.emitterSampling == EmitterSampling::Brdf) return 1.0f;
  if (p_.emitterSampling == EmitterSampling::Light) return 0.0f;
  const float cosL = std::abs(dot(emitters_->triangles()[size_t(hit.emitter)].normal, hit.wo));
  if (!(cosL > 0.0f)) return 0.0f;
  const float pdfLight = emitters_->pdfArea(hit.emitter) * hit.t * hit.t / cosL;
  return powerHeuristic(pdfBrdf, pdfLight);
}

vec3 ReferenceRenderer::pathLi(vec3 o, vec3 d, Pcg32& rng, vec3& indirect) const {
  vec3 L(0.0f), beta(1.0f);
  // The throughput of the light that reaches x0 along one segment (the direct channel's terms met
  // at depth 1): beta itself unless glossy=direct, where beta keeps x0's diffuse part only.
  vec3 betaSegment(1.0f);
  float pdfBrdf = 0;  // of the direction that led to this vertex (none for the camera ray)
  // Light that reaches the first vertex x0 along one segment (its emission
  // and NEE, emitters and environment met by its bounce ray) is direct; the
  // rest, from the second vertex on, is indirect.
  SurfacePoint prev;  // the vertex the current ray leaves (depth ≥ 1)
  for (int depth = 0;; ++depth) {
    SurfacePoint sp;
    bool found;
    if (voxelTracer_ && depth >= 1) {
      // visibility=voxels: the first hit of the bounce ray through the voxel
      // grid, then the surface there found exactly (within two voxel
      // diagonals of the hit voxel's entry; none: the path ends).
      TraceRay ray;
      ray.origin = prev.p + prev.n * (p_.offset * voxelDiagonal_);
      ray.dir = d;
      ray.tmax = 4.0f * sceneDiagonal_;
      const TraceResult h = voxelTracer_->trace(ray);
      if (h.hit && !intersect(ray.origin, d, h.t + 2.0f * voxelDiagonal_, sp)) break;
      found = h.hit;
    } else {
      found = intersect(o, d, 1e30f, sp);
    }
    if (!found) {
      // The camera sees the environment as background always; as a light only with env.
      if (depth == 0 || p_.env) {
        const bool isIndirect = depth >= 2 || (depth == 1 && p_.envIndirect);
        const vec3 e = (depth == 1 && !isIndirect ? betaSegment : beta) * scene_->environmentRadiance(d);
        L += e;
        if (isIndirect) indirect += e;
      }
      break;
    }
    if (depth >= 1 && p_.glossy != GlossyModel::All) sp.brdf.ks = vec3(0.0f);  // bounce surfaces: diffuse
    if (sp.emission != vec3(0.0f)) {
      const vec3 e =
          (depth == 1 ? betaSegment : beta) * sp.emission * (depth == 0 ? 1.0f : emissionWeight(sp, pdfBrdf));
      L += e;
      if (depth >= 2) indirect += e;
    }
    if (depth == p_.maxDepth) break;
    const vec3 nee = beta * directLight(sp, rng, true);
    L += nee;
    if (depth >= 1) indirect += nee;
    vec3 wi = sampleBrdf(sp.brdf, sp.n, sp.wo, rng.uniform3());
    float pdf = brdfPdf(sp.brdf, sp.n, sp.wo, wi);
    if (!(pdf > 0.0f) || dot(wi, sp.n) <= 0.0f || dot(wi, sp.ng) <= 0.0f) break;
    const float cosPdf = dot(wi, sp.n) / pdf;
    betaSegment = beta * evalBrdf(sp.brdf, sp.n, sp.wo, wi) * cosPdf;
    // glossy=direct: x0's indirect light through its diffuse lobe only (the direction still
    // drawn from the whole BRDF, so the direct light's MIS is the same as glossy=all's).
    beta = depth == 0 && p_.glossy == GlossyModel::Direct
               ? beta * evalBrdf(diffusePart(sp.brdf), sp.n, sp.wo, wi) * cosPdf
               : betaSegment;
    pdfBrdf = pdf;
    if (depth + 1 >= p_.rrDepth) {
      const float q = russianRouletteQ(betaSegment);
      if (rng.uniform() < q) break;
      beta /= 1.0f - q;
      betaSegment /= 1.0f - q;
    }
    o = offsetOrigin(sp, wi);
    d = wi;
    prev = sp;
  }
  return L;
}

vec3 ReferenceRenderer::nearFieldLi(vec3 o, vec3 d, Pcg32& rng, vec3& indirect) const {
  SurfacePoint x;
  if (!intersect(o, d, 1e30f, x)) return scene_->environmentRadiance(d);
  vec3 L = x.emission + directLight(x, rng, true);
  vec3 wi = sampleBrdf(x.brdf, x.n, x.wo, rng.uniform3());
  float pdf = brdfPdf(x.brdf, x.n, x.wo, wi);
  if (!(pdf > 0.0f) || dot(wi, x.n) <= 0.0f || dot(wi, x.ng) <= 0.0f) return L;
  const vec3 weight = evalBrdf(x.brdf, x.n, x.wo, wi) * (dot(wi, x.n) / pdf);
  // glossy=direct: the indirect light through x's diffuse lobe only (see pathLi).
  const vec3 weightIndirect = p_.glossy == GlossyModel::Direct
                                  ? evalBrdf(diffusePart(x.brdf), x.n, x.wo, wi) * (dot(wi, x.n) / pdf)
                                  : weight;
  // The bounce surface y: its emission is direct light at x (the MIS share),
  // its direct light the one indirect bounce.
  auto bounce = [&](SurfacePoint y) {
    if (y.emission != vec3(0.0f)) L += weight * y.emission * emissionWeight(y, pdf);
    if (p_.glossy != GlossyModel::All) y.brdf.ks = vec3(0.0f);
    indirect = weightIndirect * directLight(y, rng, false);
  };
  SurfacePoint y;
  if (voxelTracer_) {
    TraceRay ray;
    ray.origin = x.p + x.n * (p_.offset * voxelDiagonal_);
    ray.dir = wi;
    ray.tmax = p_.radius;
    TraceResult h = voxelTracer_->trace(ray);
    if (!h.hit) {
      if (p_.env) indirect = weightIndirect * scene_->environmentRadiance(wi);
    } else if (intersect(ray.origin, wi, h.t + 2.0f * voxelDiagonal_, y)) {
      bounce(y);
    }
    return L + indirect;
  }
  vec3 yo = offsetOrigin(x, wi);
  if (intersect(yo, wi, p_.radius, y))
    bounce(y);
  else if (p_.env)
    indirect = weightIndirect * scene_->environmentRadiance(wi);
  return L + indirect;
}

float ReferenceRenderer::aoLi(vec3 o, vec3 d, Pcg32& rng) const {
  SurfacePoint x;
  if (!intersect(o, d, 1e30f, x)) return 0.0f;
  vec3 wi = basisToWorld(makeBasis(x.n), cosineSampleHemisphere(rng.uniform2()));
  if (dot(wi, x.ng) <= 0.0f) return 0.0f;  // below the true surface: blocked by it
  return tracer_->occluded(offsetOrigin(x, wi), wi, 0.0f, p_.radius) ? 0.0f : 1.0f;
}

vec3 ReferenceRenderer::li(vec3 o, vec3 d, Pcg32& rng, vec3& indirect) const {
  switch (p_.integrator) {
    case ExactIntegrator::Path:
    case ExactIntegrator::Direct:
      return pathLi(o, d, rng, indirect);
    case ExactIntegrator::NearField:
      return nearFieldLi(o, d, rng, indirect);
    case ExactIntegrator::Ao:
      return vec3(aoLi(o, d, rng));
  }
  return vec3(0.0f);
}

void ReferenceRenderer::prepareFrame(Frame& f) {
  scene_ = &f.scene;
  flat_ = &f.resources.get<FlatScene>();
  tracer_ = &f.resources.get<EmbreeTracer>();
  emitters_ = &f.resources.get<Emitters>();
  voxelTracer_.reset();
  if (p_.voxelVisibility) {
    TracerInputs in;
    in.pyramid = &f.resources.get<OrMipPyramid>();
    voxelTracer_ = createTracer("hierarchical", in);
    voxelDiagonal_ = f.resources.get<GridBox>().voxelDiagonal();
  }
  sceneDiagonal_ = f.scene.bounds(f.request.time).diagonal();
  lights_.clear();
  for (auto& l : f.scene.lights) lights_.push_back(packLight(l));
  eps_ = 2e-5f * f.scene.bounds(f.request.time).diagonal();
  view_ = pinholeView(f.scene.cameraAt(f.request.time), f.width(), f.height());
}

bool ReferenceRenderer::addSample(Frame& f, int k) {
  const int W = f.width(), H = f.height(), tile = 16;
  const int tilesX = (W + tile - 1) / tile, tilesY = (H + tile - 1) / tile;
  vec3* image = f.samplePixels("image");
  vec3* indirectOut = f.wants("indirect") ? f.samplePixels("indirect") : nullptr;
  vec3* directOut = f.wants("direct") ? f.samplePixels("direct") : nullptr;
  const uint32_t seed = f.request.seed;
  auto s = f.profiler.scope("render");
  parallelFor(size_t(tilesX) * tilesY, 1, f.request.threads, [&](size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t) {
      if (interruptRequested()) return;
      const int x0 = int(t % size_t(tilesX)) * tile, y0 = int(t / size_t(tilesX)) * tile;
      for (int y = y0; y < std::min(y0 + tile, H); ++y)
        for (int x = x0; x < std::min(x0 + tile, W); ++x) {
          const size_t pix = size_t(y) * W + x;
          // Every (pixel, sample) owns a stream: the image is the same for any thread count.
          Pcg32 rng(uint64_t(seed) * 0x9E3779B97F4A7C15ULL + pix, uint64_t(k));
          vec2 j = rng.uniform2();
          float px = (2.0f * (x + j.x) / W - 1.0f) * view_.tanHalf * view_.aspect;
          float py = (1.0f - 2.0f * (y + j.y) / H) * view_.tanHalf;
          vec3 d = glm::normalize(view_.fwd + px * view_.right + py * view_.up);
          vec3 indirect(0.0f);
          vec3 L = li(view_.origin(d), d, rng, indirect);
          if (!std::isfinite(L.x) || !std::isfinite(L.y) || !std::isfinite(L.z))
            throw std::logic_error("reference: non-finite radiance");
          image[pix] = L;
          if (indirectOut) indirectOut[pix] = indirect;
          if (directOut) directOut[pix] = L - indirect;
        }
    }
  });
  return !interruptRequested();
}

void ReferenceRenderer::finishFrame(Frame& f) {
  f.extra["threads"] = resolveThreads(f.request.threads);
  if (voxelTracer_) f.extra["voxel_diagonal"] = voxelDiagonal_;
  f.extra["triangles"] = flat_->triangleCount();
  f.extra["emitter_triangles"] = emitters_->size();
}

}  // namespace

MethodInfo referenceMethod() {
  return {"reference",
          "CPU Embree reference: integrator=path|nearfield|ao|direct",
          false,
          [](ParamSet& p, const Scene& s) -> std::unique_ptr<Method> {
            return std::make_unique<ReferenceRenderer>(p, s);
          },
          {},
          "reference_gl"};
}

}  // namespace vgi
