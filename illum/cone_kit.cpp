#include "illum/cone_kit.h"

#include <glad/gl.h>

#include <cmath>
#include <cstring>

#include "core/error.h"
#include "core/gpu_scene.h"
#include "core/params.h"
#include "core/shader_library.h"
#include "illum/light_maps.h"
#include "illum/sample_loop.h"
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
    s.radiance =
        p.getString("radiance", "inject",
                    "voxel radiance: inject (conservative rasterization lit through the shadow maps, "
                    "the VCT thesis) or atlas (the atlas voxelizer's radiance channel, VGI 3; needs "
                    "voxelizer=atlas)",
                    {"inject", "atlas"});
  else
    s.radiance = "none";
  s.grid = readBinaryGridParams(p, 4, false, s.radiance == "atlas" ? "atlas" : "conservative");
  s.grid.cubicCells = true;
  if (s.radiance == "atlas" && s.grid.voxelizer != "atlas")
    fail("parameter 'voxelizer': '", s.grid.voxelizer,
         "' with radiance=atlas (the radiance channel comes from the atlas voxelizer's points: "
         "voxelizer=atlas)");
  // Bytes per cell: sums 16 + counts 4, the count texture 4, occupancy ≈ 1.14,
  // radiance 8 × 8/7, six faces of an eighth each 8 × 8/7.
  const double cells = double(s.grid.resolution.x) * s.grid.resolution.y * s.grid.resolution.z;
  s.anisotropic = p.getBool("anisotropic", anisotropicDefault,
                            "six-direction anisotropic mip chain (front-to-back per axis direction, VCT "
                            "thesis 3.2); false: isotropic 2x2x2 means");
  const double gib = cells * (24.0 + 1.15 + 9.15 + (s.anisotropic ? 6.9 : 0.0)) / double(1u << 30);
  if (gib > 8.0)
    fail("parameter 'voxels': ", s.grid.resolution.x, "x", s.grid.resolution.y, "x", s.grid.resolution.z,
         " needs ", gib, " GiB for the cone-tracing volume (at most 8 GiB)");
  s.absWeights =
      p.getString("face_weights", absWeightsDefault ? "abs" : "squared",
                  "anisotropic lookups mix the three faces by abs (|d|, the VCT thesis; an oblique "
                  "wall stays opaque) or squared (d^2, summing to 1)",
                  {"abs", "squared"}) == "abs";
  s.step =
      p.getFloat("step", stepDefault, "cone march step, in cone diameters (at least a voxel)", 0.05f, 8.0f);
  readShadowParams(p, s.shadow);
  return s;
}

void addConeVolumeNeeds(SceneNeeds& n, const ConeVolumeSettings& s) {
  n.lightMaps = LightMapNeed{s.shadow.resolution, false};
  n.binaryGrid = s.grid;
  n.orMipPyramid = true;
  if (s.radiance == "atlas")
    n.valueGrids = ValueGridNeed{{"radiance"}, s.anisotropic ? ValueMips::Anisotropic : ValueMips::Isotropic};
}

const ValueTextures& ConeVolume::textures(const Frame& f) const {
  return s_.radiance == "atlas" ? f.resources.valueTextures() : *own_;
}

void ConeVolume::update(Frame& f, const ConeVolumeSettings& s) {
  s_ = s;
  const GridBox& box = f.resources.gridBox();
  const glm::vec3 v = box.voxelSize();
  voxel_ = std::max({v.x, v.y, v.z});
  if (s.radiance == "atlas") return;  // the scene resources keep it current
  const bool lit = s.radiance == "inject";
  if (!dirty_ && (!lit || f.resources.lightMaps().renders() == renders_)) return;
  dirty_ = false;
  ShaderLibrary& shaders = f.shaders();
  if (!own_) {
    own_ = std::make_unique<ValueTextures>(box, std::vector<std::string>{"radiance"},
                                           s.anisotropic ? ValueMips::Anisotropic : ValueMips::Isotropic);
    counts_ = makeBuffer(size_t(box.cellCount()) * 4);
    sums_ = makeBuffer(size_t(box.cellCount()) * 16);
    max_ = makeBuffer(4);
    const std::vector<std::string> files = {"voxelize/conservative.vert.glsl",
                                            "voxelize/conservative.geom.glsl", "illum/vct/inject.frag.glsl"};
    prog_ = shaders.program(files, {{"CONSERVATIVE_VALUES", "1"}});
    maxProg_ = shaders.program(files, {{"CONSERVATIVE_VALUES", "1"}, {"INJECT_MAX", "1"}});
  }
  const uint32_t zero = 0;
  glClearNamedBufferData(counts_.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  glClearNamedBufferData(sums_.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  if (lit) {
    renders_ = f.resources.lightMaps().renders();
    inject(f);
  }
  ValueSumBuffers b;
  b.counts = counts_.get();
  b.sums[3] = sums_.get();
  b.radianceMax = radianceMax_;
  own_->resolve(b, shaders, f.profiler, f.resources.glPyramid().words());
}

void ConeVolume::inject(Frame& f) {
  ShaderLibrary& shaders = f.shaders();
  const GridBox& box = f.resources.gridBox();
  const int side = int(std::max({box.resolution.x, box.resolution.y, box.resolution.z}));
  const GpuScene& gpu = f.resources.gpuScene();
  auto draw = [&](unsigned prog) {
    setGridUniforms(shaders, prog, box);
    shaders.setUniform(prog, "uViewport", float(side));
    shaders.setUniform(prog, "uShadowBias", s_.shadow.bias);
    shaders.setUniform(prog, "uNormalOffset", s_.shadow.normalOffset);
    drawWithoutAttachments(side, side, [&] {
      glUseProgram(prog);
      gpu.bind(shaders, prog);
      f.resources.lightMaps().bind();
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VALUE_RADIANCE_MAX, max_.get());
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VALUE_COUNTS, counts_.get());
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VALUE_RADIANCE, sums_.get());
      gpu.draw();
    });
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  };
  {
    // Pass 1: the largest radiance of any (triangle, cell) pair: the fixed-point range.
    auto s = f.profiler.scope("vct_inject_max");
    const uint32_t zero = 0;
    glClearNamedBufferData(max_.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    draw(maxProg_);
    uint32_t bits = 0;
    glGetNamedBufferSubData(max_.get(), 0, 4, &bits);
    std::memcpy(&radianceMax_, &bits, 4);
    if (!(radianceMax_ > 0.0f) || !std::isfinite(radianceMax_)) radianceMax_ = 1.0f;  // unlit: sums stay 0
  }
  auto s = f.profiler.scope("vct_inject");
  shaders.setUniform(prog_, "uRadianceMax", radianceMax_);
  draw(prog_);
  stats_["radiance_max"] = radianceMax_;
}

void ConeVolume::addDefines(const ConeVolumeSettings& s, ShaderDefines& defs) {
  if (s.anisotropic) defs["VCT_ANISOTROPIC"] = "1";
  if (s.absWeights) defs["VCT_ABS_WEIGHTS"] = "1";
}

namespace {
void bindVolume(const ValueTextures& t, ShaderLibrary& shaders, unsigned prog, float step) {
  t.bind();
  if (t.mips() == ValueMips::Anisotropic) t.bindAniso("radiance");
  setGridUniforms(shaders, prog, t.box());
  const glm::vec3 v = t.box().voxelSize();
  shaders.setUniform(prog, "uVoxelSize", std::max({v.x, v.y, v.z}));
  shaders.setUniform(prog, "uMaxLod", float(t.levels() - 1));
  shaders.setUniform(prog, "uConeStep", step);
}
}  // namespace

void ConeVolume::bind(Frame& f, ShaderLibrary& shaders, unsigned prog) const {
  bindVolume(textures(f), shaders, prog, s_.step);
}

std::vector<ProbeResult> traceConesGl(const ValueTextures& volume, ShaderLibrary& shaders,
                                      const std::vector<ProbeCone>& cones, float step, bool skipEmpty,
                                      float mediumAlpha) {
  ShaderDefines defs;
  if (volume.mips() == ValueMips::Anisotropic) defs["VCT_ANISOTROPIC"] = "1";
  if (mediumAlpha >= 0.0f) defs["UNIFORM_MEDIUM"] = "1";
  const unsigned prog = shaders.program({"illum/vct/probe.comp.glsl"}, defs);
  glUseProgram(prog);
  bindVolume(volume, shaders, prog, step);
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
