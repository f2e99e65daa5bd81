// `vct_ao`: ambient occlusion by approximate voxel cone tracing as the VCT-AO
// thesis evaluates it (Basgier 2015, ../shared/papers/003_…, §5.2 and
// §6.3.1, after Crassin et al. 2011): a few wide cones per pixel through the
// opacity volume (illum/cone_kit: radiance=none; the opacity of any binary
// voxelizer, default hybrid: the conservative cells, small triangles set
// triangle-parallel, §3.4–3.5), front-to-back accumulation of opacity
// with the distance falloff f(t) = 1/(1 + λ t / r), AO the cosine-weighted
// mean of the cones' transparency.
//   Constellations (`cones`): 3 (a ring of three at 45°), 5 (the normal +
//   four along ± tangent and ± bitangent at 55°; 90° apertures) and 8 (the
//   normal + seven at 60°; 60° apertures), aligned to the normal / tangent /
//   bitangent, each axis weighted by its share of the cosine-weighted
//   hemisphere (illum/cone_kit: coneWeights).
//   The thesis' remedies for the quad-like artefacts: local jitter (a
//   per-pixel pseudo-random azimuth of the constellation) and overlapping
//   cones (`overlap` widens every aperture).
//   Cone length `radius` (the thesis compares at 0.3 of the scene diagonal;
//   the default here), origin offset 1.5 voxel diagonals.
//   Deviation, measured (docs/BENCHMARKS.md): the anisotropic chain by default
//   (the thesis' octree holds one isotropic value per node; isotropic means
//   thin a one-voxel wall to 2^-l at level l, so cones see through walls:
//   Cornell AO energy 1.41 of the exact against 0.98 anisotropic), and the
//   faces mixed by d² (`face_weights=squared`; the thesis' |d| weights sum to
//   up to √3 and over-occlude: energy 0.80). `vct` keeps |d|, which its
//   radiance needs (closed sphere: 0.92 of the bounce against 0.75); and
//   steps of half a cone diameter (the AO's samples at a whole diameter alias
//   with the voxel lattice into a plaid pattern the jitter does not remove).
// The gather kit runs it at 1, ½ or ¼ resolution with its blur and joint
// bilateral upsampling; the constellation also turns per interleave set and per
// sample (`vgi render --spp N` averages azimuths).
// Counterpart: reference integrator=ao with the same radius (falloff 0: the
// same integral, cosine-weighted unoccluded fraction within r).
//
// Parameters: `vgi render --help-module vct_ao` (and docs/PARAMETERS.md), generated from the
// ParamSet declarations (this file's and its kits'), whose doc strings are the one place they are written.
#include "illum/methods/vct_ao.h"

#include <glad/gl.h>

#include <cmath>

#include "core/error.h"
#include "core/shader_library.h"
#include "illum/framework/compute_pass.h"
#include "illum/framework/deferred.h"
#include "illum/framework/sample_loop.h"
#include "illum/kits/cone_kit.h"
#include "illum/kits/gather_kit.h"
#include "illum/resources/gpu_scene.h"
#include "shaders/illum/vct_ao/params.glsl"

namespace vgi {

namespace {

constexpr float kVctAoRadius = 0.3f;  // of the scene diagonal (the thesis' comparison)

class VctAoMethod : public Method {
 public:
  VctAoMethod(ParamSet& p, const Scene& scene) {
    cones_ = p.getInt("cones", 8, "cone constellation: 3, 5 or 8 cones", 3, 8);
    if (cones_ != 3 && cones_ != 5 && cones_ != 8)
      fail("parameter 'cones': ", cones_, " is not one of 3, 5, 8");
    const float defAperture = cones_ == 3 ? 120.0f : cones_ == 5 ? 90.0f : 60.0f;
    aperture_ = p.getFloat(
        "aperture", defAperture,
        "full opening angle of the cones, degrees (default 120 / 90 / 60 for 3 / 5 / 8 cones)", 1.0f, 179.0f);
    overlap_ = p.getFloat("overlap", 1.0f, "aperture multiplier (> 1: overlapping cones, the thesis' remedy)",
                          0.1f, 4.0f);
    if (aperture_ * overlap_ >= 179.5f)
      fail("parameters 'aperture' x 'overlap': ", aperture_ * overlap_, " degrees (must stay under 179.5)");
    jitter_ =
        p.getBool("jitter", true, "per-pixel pseudo-random azimuth of the constellation (local jitter)");
    radius_ = p.getFloat("radius", kVctAoRadius * scene.bounds().diagonal(),
                         "cone length r, world units (default 0.3 x scene diagonal)", 1e-30f, 1e30f);
    falloff_ = p.getFloat("falloff", 0.0f, "distance falloff lambda of 1/(1 + lambda t / r)", 0.0f, 1e6f);
    guard_ = p.getBool("plane_guard", true,
                       "cap a cone sample's mip level so it cannot reach the receiver's tangent plane (ours; "
                       "false: the thesis' cones)");
    offset_ = readOffset(p, 1.5f,
                         "1.5, as the VCT-AO thesis (§6.2): enough to keep its cones from stopping early on "
                         "self-occlusion");
    vol_ = readConeVolumeParams(p, false, true, false, 0.5f);
    gather_ = readGatherParams(p, "AO cone", false, false, 2);
    temporal_ = readTemporal(p);
    constellation_ = cones_ == 3   ? ringConstellation(false, 3, 45.0f)
                     : cones_ == 5 ? ringConstellation(true, 4, 55.0f)
                                   : ringConstellation(true, 7, 60.0f);
  }
  SceneNeeds needs() const override {
    SceneNeeds n;
    needGBuffer(n);
    vol_.addNeed(n);  // radiance=none: opacity only
    return n;
  }
  void prepareFrame(Frame& f) override {
    kit_.prepare(f, gather_);
    ShaderDefines defs;
    vol_.addDefines(defs);
    ao_.create(f, {"illum/vct_ao/ao.comp.glsl"}, defs, {gbufferInput});
    GatherKit::checkPass(ao_);
    shared::VctAoParams& p = ao_.params();
    VGI_CHECK(constellation_.size() <= std::size(p.cones));
    std::copy(constellation_.begin(), constellation_.end(), p.cones);
    p.tanHalf = std::tan(glm::radians(aperture_ * overlap_) * 0.5f);
    p.radius = radius_;
    p.offset = offset_ * f.resources.get<GridBox>().voxelDiagonal();
    p.falloff = falloff_;
    p.seed = f.request.seed;
    p.guard = guard_ ? 1 : 0;
  }
  bool addSample(Frame& f, int k) override {
    {
      auto s = f.profiler.scope("ao_cones");
      const int ring = cones_ == 3 ? 3 : cones_ - 1;
      const float period = 2.0f * float(M_PI) / float(ring);
      ao_.params().turn = k == 0 ? 0.0f : period * halton(k, 3);
      ao_.params().jitter = jitter_ ? period : 0.0f;
      ao_.use(f);
      f.resources.get<ConeSource>().bind(f.shaders(), ao_.program(), vol_.step);
      kit_.dispatchGather(int(constellation_.size()), 16);
    }
    kit_.resolve(f);
    return true;
  }
  void finishFrame(Frame& f) override {
    f.extra["radius"] = radius_;
    f.extra["offset_world"] = offset_ * f.resources.get<GridBox>().voxelDiagonal();
    f.extra["aperture_deg"] = aperture_ * overlap_;
    f.extra["ao_size"] = {kit_.width(), kit_.height()};
    nlohmann::json cones = nlohmann::json::array();
    for (auto& c : constellation_) cones.push_back({c.x, c.y, c.z, c.w});
    f.extra["constellation"] = cones;
  }

  TemporalSettings temporal() const override { return temporal_; }

 private:
  TemporalSettings temporal_;
  int cones_ = 8;
  float aperture_ = 60, overlap_ = 1, radius_ = 1, falloff_ = 0, offset_ = 1.5f;
  bool jitter_ = true, guard_ = true;
  ConeVolumeSettings vol_;
  GatherSettings gather_;
  std::vector<glm::vec4> constellation_;
  GatherKit kit_;
  ComputePass<shared::VctAoParams> ao_;
};

}  // namespace

MethodInfo vctAoMethod() {
  return {
      "vct_ao",
      "GL ambient occlusion by voxel cone tracing: 3/5/8-cone constellations, local jitter, overlap "
      "(Basgier "
      "2015)",
      true,
      [](ParamSet& p, const Scene& s) -> std::unique_ptr<Method> {
        return std::make_unique<VctAoMethod>(p, s);
      },
      [](const nlohmann::json& p) {
        // Occlusion within the radius is the quantity itself: the model leaves nothing out.
        const std::vector<std::string> ao = {"integrator=ao", "radius=" + counterpartText(p.at("radius"))};
        return Counterpart{"reference", ao, {}, "", ao};
      }};
}

}  // namespace vgi
