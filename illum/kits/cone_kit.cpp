#include "illum/kits/cone_kit.h"

#include <glad/gl.h>

#include <cmath>
#include <functional>

#include "core/error.h"
#include "core/params.h"
#include "core/shader_library.h"
#include "shaders/shared/bindings.glsl"
#include "shaders/shared/sampling.glsl"
#include "traverse/gl_ray_tracer.h"
#include "voxelize/gpu_grid.h"
#include "voxelize/value_textures.h"

namespace vgi {

ConeVolumeSettings readConeVolumeParams(ParamSet& p, bool withRadiance, bool anisotropicDefault,
                                        bool absWeightsDefault, float stepDefault) {
  ConeVolumeSettings s;
  if (withRadiance)
    s.radiance = coneRadianceOf(
        p.getString("radiance", "inject",
                    "voxel radiance: inject (conservative rasterization lit through the shadow maps, "
                    "the VCT thesis), texels (each texel of reflective shadow maps into its cell, the "
                    "2013 article; holes where the maps are coarser than the voxels) or atlas (the atlas "
                    "voxelizer's radiance channel, VGI 3; needs voxelizer=atlas)",
                    {"inject", "texels", "atlas"}));
  else
    s.radiance = ConeRadiance::None;
  const bool atlas = s.radiance == ConeRadiance::Atlas;
  // hybrid: the conservative rasterization's cells (to float rounding at contacts), the small triangles
  // set in the geometry shader — a tenth of its time on the bunny and Sibenik (docs/BENCHMARKS.md).
  s.grid = readBinaryGridParams(p, 4, false, atlas ? "atlas" : "hybrid");
  s.grid.cubicCells = true;
  if (atlas && s.grid.voxelizer != "atlas")
    fail("parameter 'voxelizer': '", s.grid.voxelizer,
         "' with radiance=atlas (the radiance channel comes from the atlas voxelizer's points: "
         "voxelizer=atlas)");
  const bool svo =
      p.getString("volume", "dense",
                  "the volume's storage: dense (3D textures with mip chains) or svo (a sparse voxel "
                  "octree with 3x3x3 bricks, Crassin et al. 2011; the same values at the same "
                  "resolution)",
                  {"dense", "svo"}) == "svo";
  s.volume = svo ? ConeVolumeSettings::Storage::Svo : ConeVolumeSettings::Storage::Dense;
  s.dilate = p.getBool("dilate", true,
                       "svo: also allocate the empty nodes whose bricks a trilinear sample next to a filled "
                       "neighbour needs (the dense volume's samples exactly; false: the articles' tree, "
                       "with the filled/empty brick-border artefact)");
  s.updateEvery = p.getInt("update_every", 1,
                           "svo, dynamic scenes: rebuild the octree at every k-th frame whose grid changed "
                           "(in between the last tree is lit)",
                           1, 1000);
  if (svo) {
    if (atlas)
      fail(
          "parameter 'radiance': 'atlas' with volume=svo (the octree's leaves are lit by injection: "
          "radiance=inject)");
    svoDepth(s.grid.resolution);  // names the resolution past the octree's 1024 cells per axis
  }
  // Bytes per cell: sums 16 + counts 4, the count texture 4, occupancy ≈ 1.14,
  // radiance 8 × 8/7, six faces of an eighth each 8 × 8/7.
  const double cells = double(s.grid.resolution.x) * s.grid.resolution.y * s.grid.resolution.z;
  s.anisotropic = p.getBool("anisotropic", anisotropicDefault,
                            "six-direction anisotropic mip chain (front-to-back per axis direction, VCT "
                            "thesis 3.2); false: isotropic 2x2x2 means");
  if (withRadiance) {
    // level0 where it applies: lower error on Sibenik, the closed sphere's bounce unchanged; level1
    // also halves the leak through walls at 5-20 % of the bounce (docs/BENCHMARKS.md, "Leaks: vct").
    const char* why = s.radiance != ConeRadiance::Inject ? "radiance=inject"
                      : svo                              ? "volume=dense"
                      : !s.anisotropic                   ? "anisotropic=true"
                                                         : nullptr;
    const std::string d = p.getString(
        "directional", why ? "none" : "level0",
        "radiance seen from the cone's side: each voxel keeps the direction its injected light leaves in, "
        "so a wall voxel lit on one face does not glow from the other (ours): none, level0 (the cones' "
        "level-0 samples) or level1 (and the anisotropic chain's first level: half the leak through "
        "walls, less light on curved and oblique surfaces); needs radiance=inject, volume=dense, "
        "anisotropic (level0 there by default)",
        {"none", "level0", "level1"});
    s.directional = d != "none";
    s.directionalChain = d == "level1";
    if (s.directional && why)
      fail("parameter 'directional': ", d, " needs ", why, " (radiance=", coneRadianceName(s.radiance),
           ", volume=", svo ? "svo" : "dense", ", anisotropic=", s.anisotropic ? "true" : "false", ")");
  }
  if (withRadiance) {
    s.injectSmall =
        p.getInt("inject_small", 27,
                 "radiance=inject: a triangle whose bounding box spans at most this many cells is lit "
                 "triangle-parallel in the geometry shader (the same (triangle, cell) pairs as the "
                 "conservative rasterization, without rasterizing it: a third to a half of the "
                 "injection's time where triangles are small; 27, a 3x3x3 box, was the fastest on "
                 "Sibenik at 128^3 and 256^3); 0: every triangle through the rasterization",
                 0, 512);
    if (p.has("inject_small") && s.radiance != ConeRadiance::Inject)
      fail("parameter 'inject_small': needs radiance=inject (radiance=", coneRadianceName(s.radiance), ")");
  }
  // directional: its sums 16 and its texture 4.
  const double gib = cells *
                     (24.0 + 1.15 + 9.15 + (s.anisotropic ? 6.9 : 0.0) + (s.directional ? 20.0 : 0.0)) /
                     double(1u << 30);
  if (!svo && gib > 8.0)
    fail("parameter 'voxels': ", s.grid.resolution.x, "x", s.grid.resolution.y, "x", s.grid.resolution.z,
         " needs ", gib, " GiB for the cone-tracing volume (at most 8 GiB)");
  s.absWeights =
      p.getString("face_weights", absWeightsDefault ? "abs" : "squared",
                  "anisotropic lookups mix the three faces by abs (|d|, the VCT thesis; an oblique "
                  "wall stays opaque) or squared (d^2, summing to 1)",
                  {"abs", "squared"}) == "abs";
  s.step =
      p.getFloat("step", stepDefault, "cone march step, in cone diameters (at least a voxel)", 0.05f, 8.0f);
  s.maxLevel = p.getInt("max_level", -1,
                        "the highest mip level a cone samples, the step following the footprint sampled "
                        "(coarse texels average both sides of a wall: a cap trades light leaks for steps; "
                        "-1: the chain's last)",
                        -1, 16);
  readShadowParams(p, s.shadow);
  return s;
}

ConeVolumeNeed ConeVolumeSettings::need() const {
  ConeVolumeNeed n;
  n.grid = grid;
  if (radiance == ConeRadiance::Atlas) n.grid.values = {"radiance"};
  n.radiance = radiance;
  n.anisotropic = anisotropic;
  n.directional = directional;
  n.directionalChain = directionalChain;
  if (radiance != ConeRadiance::None)
    n.lightMaps = LightMapNeed{shadow.resolution, radiance == ConeRadiance::Texels};
  if (injectsRadiance(radiance)) {
    n.bias = shadow.bias;
    n.normalOffset = shadow.normalOffset;
    n.injectSmall = injectSmall;
  }
  return n;
}

SparseOctreeNeed ConeVolumeSettings::octreeNeed() const {
  const ConeVolumeNeed d = need();
  SparseOctreeNeed n;
  n.grid = d.grid;
  n.radiance = radiance;
  n.anisotropic = anisotropic;
  n.dilate = dilate;
  n.updateEvery = updateEvery;
  n.lightMaps = d.lightMaps;
  n.bias = d.bias;
  n.normalOffset = d.normalOffset;
  n.injectSmall = d.injectSmall;
  return n;
}

void ConeVolumeSettings::addNeed(SceneNeeds& needs) const {
  if (volume == Storage::Svo)
    needs.add(octreeNeed());
  else
    needs.add(need());
}

void ConeVolumeSettings::addDefines(ShaderDefines& defs) const {
  if (volume == Storage::Svo) defs["CONE_SVO"] = "1";
  if (anisotropic) defs["VCT_ANISOTROPIC"] = "1";
  if (directional) defs["VCT_DIRECTIONAL"] = "1";
  if (maxLevel >= 0) defs["VCT_MAX_LEVEL"] = std::to_string(maxLevel);
  if (absWeights) defs["VCT_ABS_WEIGHTS"] = "1";
}

namespace {
std::vector<ProbeResult> traceCones(ShaderDefines defs, const std::function<void(unsigned)>& bind,
                                    ShaderLibrary& shaders, const std::vector<ProbeCone>& cones,
                                    bool skipEmpty, float mediumAlpha) {
  if (mediumAlpha >= 0.0f) defs["UNIFORM_MEDIUM"] = "1";
  const unsigned prog = shaders.program({"illum/vct/probe.comp.glsl"}, defs);
  glUseProgram(prog);
  bind(prog);
  if (mediumAlpha >= 0.0f) shaders.setUniform(prog, "uMediumAlpha", mediumAlpha);
  shaders.setUniform(prog, "uCount", unsigned(cones.size()));
  shaders.setUniform(prog, "uSkipEmpty", skipEmpty ? 1 : 0);
  std::vector<glm::vec4> in;
  for (auto& c : cones) {
    in.emplace_back(c.apex, c.tanHalf);
    in.emplace_back(c.dir, c.length);
  }
  const size_t n = std::max<size_t>(cones.size(), 1);
  GlBuffer a = makeBuffer(n * 32), b = makeBuffer(n * 32);
  if (!in.empty()) glNamedBufferSubData(a.get(), 0, GLsizeiptr(in.size() * 16), in.data());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_TRACE_RAYS, a.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_TRACE_HITS, b.get());
  glDispatchCompute(unsigned(n + 63) / 64, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<ProbeResult> out(cones.size());
  if (!out.empty()) glGetNamedBufferSubData(b.get(), 0, GLsizeiptr(out.size() * 32), out.data());
  return out;
}
}  // namespace

std::vector<ProbeResult> traceConesGl(const ValueTextures& volume, ShaderLibrary& shaders,
                                      const std::vector<ProbeCone>& cones, float step, bool skipEmpty,
                                      float mediumAlpha) {
  ShaderDefines defs;
  if (volume.mips() == ValueMips::Anisotropic) defs["VCT_ANISOTROPIC"] = "1";
  return traceCones(
      defs, [&](unsigned prog) { bindConeVolume(volume, shaders, prog, step); }, shaders, cones, skipEmpty,
      mediumAlpha);
}

std::vector<ProbeResult> traceConesGl(const SparseVoxelOctree& octree, ShaderLibrary& shaders,
                                      const std::vector<ProbeCone>& cones, float step, bool skipEmpty) {
  ShaderDefines defs{{"CONE_SVO", "1"}};
  if (octree.anisotropic()) defs["VCT_ANISOTROPIC"] = "1";
  return traceCones(
      defs, [&](unsigned prog) { bindConeOctree(octree, shaders, prog, step); }, shaders, cones, skipEmpty,
      -1.0f);
}

std::vector<glm::vec4> coneWeights(const std::vector<glm::vec3>& axes) {
  // Cosine-distributed stratified directions (each of equal weight), each
  // counted for its nearest axis; 2520 azimuths (a multiple of every ring
  // count up to 10), so symmetric rings share exactly.
  constexpr int kRadii = 400, kAzimuths = 2520;
  std::vector<double> share(axes.size(), 0.0);
  for (int j = 0; j < kAzimuths; ++j)
    for (int i = 0; i < kRadii; ++i) {
      const glm::vec3 d =
          shared::cosineSampleHemisphere(glm::vec2((i + 0.5f) / kRadii, (j + 0.5f) / kAzimuths));
      size_t best = 0;
      float bestDot = -2.0f;
      for (size_t k = 0; k < axes.size(); ++k) {
        const float c = glm::dot(d, glm::normalize(axes[k]));
        if (c > bestDot) bestDot = c, best = k;
      }
      share[best] += 1.0;
    }
  std::vector<glm::vec4> out;
  for (size_t k = 0; k < axes.size(); ++k)
    out.emplace_back(glm::normalize(axes[k]), float(share[k] / (double(kRadii) * kAzimuths)));
  return out;
}

std::vector<glm::vec4> ringConstellation(bool centre, int ring, float ringPolarDeg) {
  std::vector<glm::vec3> axes;
  if (centre) axes.emplace_back(0.0f, 0.0f, 1.0f);
  const float th = glm::radians(ringPolarDeg);
  for (int k = 0; k < ring; ++k) {
    const float ph = 2.0f * float(M_PI) * float(k) / float(ring);
    axes.emplace_back(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
  }
  return coneWeights(axes);
}

}  // namespace vgi
