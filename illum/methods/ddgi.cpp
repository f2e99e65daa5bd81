// `ddgi`: dynamic diffuse global illumination — Majercik, Guertin, Nowrouzezahrai, McGuire, "Dynamic
// Diffuse Global Illumination with Ray-Traced Irradiance Fields", JCGT 8(2), 2019: §3 the probe grid,
// §4 the update (rays per probe under a random rotation each frame, octahedral irradiance and
// distance-moment textures with a one-texel border, blended with hysteresis), §5 the query (trilinear
// weights, the smooth backface term, the Chebyshev visibility test from a biased point, the crush of
// small weights). Probe relocation and classification (`relocate`, off by default; the rule is ours,
// after the RTXGI SDK's that Majercik, Marrs, Spjut, McGuire, JCGT 10(2), 2021 describe;
// shaders/illum/ddgi/relocate.comp.glsl): back faces are told apart, probes inside geometry move out
// during the warm-up, and those still inside are left out of the shading.
//
// Needs: the G-buffer, reflective shadow maps of every light (the hits' direct light), the binary grid
// with its OR-mip pyramid and the value grids (normal, albedo) — or tracer=bvh, the scene's triangles,
// each hit reported in its grid cell. Per sample (each sample is one update of the field, as each frame
// is in the paper): the probe rays (shaders/illum/ddgi/trace.comp: each probe's `rays` directions
// through the chosen tracer, hits shaded with their direct light and the last update's field, so every
// update adds a bounce) → the irradiance and distance updates (update.comp) → deferred direct light →
// the shading (shade.comp: albedo × the field's E / π at each G-buffer point). The field lives across
// the samples and frames of a run: a still averages its samples' shading over successive updates, an
// animation's light lags behind a moving light by the hysteresis (the paper's lag). Before a run's
// first sample, `warmup` updates each replace the field (hysteresis 0), so the field holds `warmup`
// bounces; after them the hysteresis rises from 0 to its value as 1 − 1/(k + 1) over the k-th update,
// so the early field is the mean of its updates, not a blend with black. (With that mean from the
// first update on, the bounces come in slowly — field error ∝ k^(ρ − 1) — and the closed sphere of
// albedo 0.5 had 0.94 of its light after 40 updates.)
//
// The exact counterpart is `reference integrator=path glossy=direct env_channel=indirect`: every
// bounce, the receivers' and bounce surfaces' indirect light reflected diffusely (the probes store
// irradiance), the environment as indirect light (the probes gather it). It differs by the probes'
// interpolation and visibility, the voxel hits, the RSM direct light and the finite number of updates.
//
// Parameters: `vgi render --help-module ddgi` (and docs/PARAMETERS.md), generated from the ParamSet
// declarations (this file's and its kits'), whose doc strings are the one place they are written.
#include "illum/methods/ddgi.h"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>

#include "core/error.h"
#include "core/gl_handles.h"
#include "core/gpu_scene.h"
#include "core/shader_library.h"
#include "illum/framework/compute_pass.h"
#include "illum/framework/deferred.h"
#include "illum/framework/sample_loop.h"
#include "illum/kits/direct_pass.h"
#include "illum/kits/gather_kit.h"
#include "illum/kits/shared_params.h"
#include "illum/kits/tracer_kit.h"
#include "illum/resources/gpu_scene.h"
#include "illum/resources/light_maps.h"
#include "illum/resources/or_mip_pyramid.h"
#include "illum/resources/value_grids.h"
#include "shaders/illum/ddgi/params.glsl"
#include "shaders/shared/bindings.glsl"
#include "traverse/gl_ray_tracer.h"

namespace vgi {

namespace {

// The textures' rays image is `rays` × probes texels: its height bounds the probes.
constexpr int kMaxProbes = 16384;

class DdgiMethod : public Method {
 public:
  DdgiMethod(ParamSet& p, const Scene& scene) {
    probes_ = p.getInt("probes", 8,
                       "probes along the scene box's longest side (the others in proportion, >= 2)", 2, 64);
    rays_ = p.getInt("rays", 128, "rays per probe per update (each sample is one update)", 16, 1024);
    hysteresis_ = p.getFloat("hysteresis", 0.97f, "the old field's weight in each update (the paper's 0.97)",
                             0.0f, 0.999f);
    bias_ = p.getFloat("bias", 0.25f,
                       "query points move this many probe spacings along 0.2 n + 0.8 v before the "
                       "visibility test (the paper's normal and view bias)",
                       0.0f, 1.0f);
    // Off by default: a back face is told by the mesh's normal, and the framework shades one-sided
    // surfaces from both sides; a one-sided surface seen from its back (tests/illum/ddgi_test.cpp's sky
    // triangle) makes the probes on the camera's side look inside, and dropping them darkens what the
    // camera sees (0.17–0.82 of the light there).
    relocate_ = p.getBool("relocate", false,
                          "tell back faces apart by the meshes' normals, move probes out of geometry during "
                          "the warm-up and leave out those still inside (for closed, consistently oriented "
                          "meshes; false: every probe at its grid point, all used)");
    warmup_ = p.getInt("warmup", 8,
                       "updates of the field before a run's first sample, each replacing it (a bounce each)",
                       0, 1000);
    tracer_ = readTracerParam(p);
    env_ = readEnv(p);
    grid_ = readBinaryGridParams(p, 4, true);
    readShadowParams(p, shadow_);
    temporal_ = readTemporal(p);
    traceLength_ = 4.0f * scene.bounds().diagonal() + 1e-6f;
    placeProbes(scene.bounds());
  }
  std::vector<std::string> outputs() const override { return {"direct", "indirect"}; }
  SceneNeeds needs() const override {
    SceneNeeds n;
    needGBuffer(n);
    n.add(LightMapNeed{shadow_.resolution, true});
    addVoxelHitNeeds(n, grid_, tracer_, {"normal", "albedo"});  // diffuse hits: no glossy values
    return n;
  }
  void prepareFrame(Frame& f) override;
  bool addSample(Frame& f, int k) override;
  void finishFrame(Frame& f) override;
  TemporalSettings temporal() const override { return temporal_; }

 private:
  // The grid of probes over the scene box, each at the centre of its cell.
  void placeProbes(const Bounds& box);
  // One update of the field: the rays, then both atlases; with relocate, the probes' states (moved
  // when `move`).
  void update(Frame& f, uint32_t seed, float hysteresis, bool move);

  int probes_ = 8, rays_ = 128, warmup_ = 8;
  float hysteresis_ = 0.97f, bias_ = 0.25f, traceLength_ = 0;
  bool env_ = true, relocate_ = false;
  std::string tracer_;
  BinaryGridNeed grid_;
  ShadowParams shadow_;
  TemporalSettings temporal_;
  glm::ivec3 counts_{2};
  glm::vec3 origin_{0.0f}, spacing_{1.0f};
  int columns_ = 1, updates_ = 0, averaged_ = 0;  // updates since the field was cleared, since warm-up

  // The field (kept across the frames of a run) and the rays of the last update.
  GlTexture irradiance_, distance_, rays_image_;
  GlBuffer probeStates_;  // per probe: its offset (xyz) and state (w: 1 used, 0 inside geometry)
  glm::ivec2 irradianceSize_{0}, distanceSize_{0};
  // Per frame (prepareFrame).
  std::unique_ptr<DirectPass> direct_;
  ComputePass<shared::DdgiParams> trace_, updateIrradiance_, updateDistance_, relocateProbes_, shade_;
  VoxelHits hits_;
  shared::DdgiParams params_{};
};

void DdgiMethod::placeProbes(const Bounds& box) {
  const glm::vec3 size = glm::max(box.hi - box.lo, glm::vec3(0.0f));
  const float longest = std::max(1e-6f, std::max(size.x, std::max(size.y, size.z)));
  // A flat side (a floor alone, one wall) is widened to two probe spacings, so that the probes lie off
  // its surface on both sides, not in it.
  const glm::vec3 extent = glm::max(size, glm::vec3(2.0f * longest / float(probes_)));
  const glm::vec3 lo = 0.5f * (box.lo + box.hi) - 0.5f * extent;
  for (int a = 0; a < 3; ++a) counts_[a] = std::max(2, int(std::lround(probes_ * extent[a] / longest)));
  const long total = long(counts_.x) * counts_.y * counts_.z;
  if (total > kMaxProbes)
    fail("parameter 'probes': ", probes_, " gives ", counts_.x, " x ", counts_.y, " x ", counts_.z, " = ",
         total, " probes, more than ", kMaxProbes);
  spacing_ = extent / glm::vec3(counts_);
  origin_ = lo + 0.5f * spacing_;
  columns_ = int(std::ceil(std::sqrt(double(total))));
}

void DdgiMethod::prepareFrame(Frame& f) {
  ShaderLibrary& shaders = f.shaders();
  const float voxelDiagonal = f.resources.get<GridBox>().voxelDiagonal();
  direct_ =
      std::make_unique<DirectPass>(shaders, f.resources.get<GpuScene>(), shadow_.bias, shadow_.normalOffset);
  ShaderDefines defs;
  addTracerDefine(defs, tracer_);
  trace_.create(f, {"illum/ddgi/trace.comp.glsl"}, defs, {gpuSceneInput, lightMapsInput, valueTexturesInput});
  updateIrradiance_.create(f, {"illum/ddgi/update.comp.glsl"}, {}, {});
  updateDistance_.create(f, {"illum/ddgi/update.comp.glsl"}, {{"DDGI_DISTANCE", "1"}}, {});
  relocateProbes_.create(f, {"illum/ddgi/relocate.comp.glsl"}, {}, {});
  shade_.create(f, {"illum/ddgi/shade.comp.glsl"}, {}, {gbufferInput});
  shared::VoxelHitParams h{};
  h.offset = 0.0f;
  h.voxelDiagonal = voxelDiagonal;
  h.traceLength = traceLength_;
  h.glossy = 0;  // the probes store irradiance: hits reflect diffusely
  h.backProjection = shared::BACK_PROJECTION_PLANE;
  h.passThrough = 0;
  h.hitPoint = hitPointConstant("entry");
  hits_.set(trace_.program(), h);

  const int total = counts_.x * counts_.y * counts_.z;
  const int rows = (total + columns_ - 1) / columns_;
  const glm::ivec2 irr(columns_ * shared::DDGI_IRRADIANCE_TILE, rows * shared::DDGI_IRRADIANCE_TILE);
  const glm::ivec2 dist(columns_ * shared::DDGI_DISTANCE_TILE, rows * shared::DDGI_DISTANCE_TILE);
  if (!irradiance_ || irr != irradianceSize_) {  // the first frame: a field of zeros
    irradiance_ = makeTexture2D(irr.x, irr.y, GL_RGBA32F);
    distance_ = makeTexture2D(dist.x, dist.y, GL_RG32F);
    rays_image_ = makeTexture2D(rays_, total, GL_RGBA32F);
    for (unsigned t : {irradiance_.get(), distance_.get(), rays_image_.get()}) {
      glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
      glClearTexImage(t, 0, GL_RGBA, GL_FLOAT, nullptr);
    }
    const std::vector<glm::vec4> states(size_t(total), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    probeStates_ = makeBuffer(states.size() * sizeof(glm::vec4));
    glNamedBufferSubData(probeStates_.get(), 0, GLsizeiptr(states.size() * sizeof(glm::vec4)), states.data());
    irradianceSize_ = irr;
    distanceSize_ = dist;
    updates_ = 0;
    averaged_ = 0;
  }
  shared::DdgiParams& p = params_;
  p.origin = glm::vec4(origin_, bias_ * std::min(spacing_.x, std::min(spacing_.y, spacing_.z)));
  p.spacing = glm::vec4(spacing_, 1.5f * glm::length(spacing_));
  p.counts = glm::ivec4(counts_, columns_);
  p.rays = rays_;
  p.env = env_ ? 1 : 0;
  p.writeDirect = f.wants("direct") ? 1 : 0;
  p.writeIndirect = f.wants("indirect") ? 1 : 0;
  p.relocate = relocate_ ? 1 : 0;
}

void DdgiMethod::update(Frame& f, uint32_t seed, float hysteresis, bool move) {
  shared::DdgiParams& p = params_;
  // A random rotation of the directions (Shoemake's uniform quaternion from three points of a
  // low-discrepancy sequence, shifted by the seed), so the updates' rays cover the sphere.
  const glm::vec2 shift = seedShift(seed);
  const float u1 = std::fmod(halton(updates_ + 1, 2) + shift.x, 1.0f);
  const float u2 = std::fmod(halton(updates_ + 1, 3) + shift.y, 1.0f), u3 = halton(updates_ + 1, 5);
  const float a = std::sqrt(1.0f - u1), b = std::sqrt(u1), tau = 6.28318530718f;
  const glm::quat q(b * std::cos(tau * u3), a * std::sin(tau * u2), a * std::cos(tau * u2),
                    b * std::sin(tau * u3));
  const glm::mat3 R = glm::mat3_cast(glm::normalize(q));
  for (int r = 0; r < 3; ++r) p.rotation[r] = glm::vec4(R[0][r], R[1][r], R[2][r], 0.0f);  // rows
  p.hysteresis = hysteresis;
  p.move = move ? 1 : 0;
  const int total = counts_.x * counts_.y * counts_.z;
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_DDGI_PROBES, probeStates_.get());
  {
    auto s = f.profiler.scope("probe_rays");
    trace_.params() = p;
    trace_.use(f);
    bindTracer(f.resources, f.shaders(), trace_.program());
    hits_.bind();
    glBindTextureUnit(TEXUNIT_PASS_INPUT, irradiance_.get());
    glBindTextureUnit(TEXUNIT_PASS_INPUT2, distance_.get());
    glBindImageTexture(IMAGE_OUTPUT, rays_image_.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    trace_.dispatch(rays_, total, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  }
  {
    auto s = f.profiler.scope("probe_update");
    // The rays read the field through its samplers: the updates write it only after them.
    for (auto* pass : {&updateIrradiance_, &updateDistance_}) {
      const bool irradiance = pass == &updateIrradiance_;
      pass->params() = p;
      pass->use(f);
      glBindImageTexture(IMAGE_OUTPUT, irradiance ? irradiance_.get() : distance_.get(), 0, GL_FALSE, 0,
                         GL_READ_WRITE, irradiance ? GL_RGBA32F : GL_RG32F);
      glBindImageTexture(IMAGE_OUTPUT2, rays_image_.get(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
      const glm::ivec2 size = irradiance ? irradianceSize_ : distanceSize_;
      pass->dispatch(size.x, size.y, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    }
  }
  if (relocate_) {
    // After the atlases: they were filled from where the rays started.
    auto s = f.profiler.scope("probe_relocate");
    relocateProbes_.params() = p;
    relocateProbes_.use(f);
    glBindImageTexture(IMAGE_OUTPUT2, rays_image_.get(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
    relocateProbes_.dispatch(total, 1, GL_SHADER_STORAGE_BARRIER_BIT);
  }
  ++updates_;
}

bool DdgiMethod::addSample(Frame& f, int) {
  if (updates_ == 0) {
    auto s = f.profiler.scope("probe_warmup");
    for (int w = 0; w < warmup_; ++w) update(f, f.request.seed, 0.0f, true);
  }
  update(f, f.request.seed, std::min(hysteresis_, 1.0f - 1.0f / float(++averaged_)), false);
  const unsigned sample = f.sampleImage("image");
  {
    auto s = f.profiler.scope("direct");
    direct_->shade(f.gbuffer(), f.resources.get<LightMaps>(), f.camera, sample);
  }
  {
    auto s = f.profiler.scope("shade");
    params_.camera = glm::vec4(f.camera.position, 1.0f);
    shade_.params() = params_;
    shade_.use(f);
    glBindTextureUnit(TEXUNIT_PASS_INPUT, irradiance_.get());
    glBindTextureUnit(TEXUNIT_PASS_INPUT2, distance_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_DDGI_PROBES, probeStates_.get());
    bindSampleAndSplitImages(f);
    shade_.dispatch(f.width(), f.height());
  }
  return true;
}

void DdgiMethod::finishFrame(Frame& f) {
  f.extra["probe_counts"] = {counts_.x, counts_.y, counts_.z};
  f.extra["probe_spacing"] = {spacing_.x, spacing_.y, spacing_.z};
  f.extra["probe_updates"] = updates_;
  const size_t probes = size_t(counts_.x) * counts_.y * counts_.z;
  int inside = 0, moved = 0;
  if (relocate_) {  // without it the states stay as prepareFrame wrote them: no read-back (a GPU sync)
    std::vector<glm::vec4> states(probes);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(probeStates_.get(), 0, GLsizeiptr(states.size() * sizeof(glm::vec4)),
                            states.data());
    for (const glm::vec4& st : states) {
      inside += st.w == 0.0f;
      moved += st.x != 0.0f || st.y != 0.0f || st.z != 0.0f;
    }
  }
  f.extra["probes_inside"] = inside;  // left out of the shading
  f.extra["probes_moved"] = moved;
  f.extra["rays_per_update"] = uint64_t(counts_.x) * counts_.y * counts_.z * rays_;
  const double texels = double(irradianceSize_.x) * irradianceSize_.y * 16.0 +
                        double(distanceSize_.x) * distanceSize_.y * 8.0 +
                        double(rays_) * double(probes) * 16.0 + double(probes) * 16.0;
  f.addStateBytes(texels);
}

}  // namespace

MethodInfo ddgiMethod() {
  return {"ddgi",
          "GL irradiance probes with ray-traced visibility, multi-bounce diffuse (Majercik et al. 2019)",
          true,
          [](ParamSet& p, const Scene& s) -> std::unique_ptr<Method> {
            return std::make_unique<DdgiMethod>(p, s);
          },
          [](const nlohmann::json&) {
            std::vector<std::string> set = fullPathReference("indirect");
            set.push_back("glossy=direct");
            return Counterpart{"reference",
                               set,
                               {"direct", "indirect"},
                               "every bounce, reflected diffusely but the visible surface's direct light "
                               "(glossy=direct: the probes store irradiance); the environment is indirect "
                               "light (the probes gather it)",
                               fullPathReference("indirect")};
          }};
}

}  // namespace vgi
