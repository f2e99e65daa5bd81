#include "illum/resources/cone_volume.h"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/gpu_memory.h"
#include "core/gpu_scene.h"
#include "core/profiler.h"
#include "core/scene.h"
#include "core/shader_library.h"
#include "shaders/shared/bindings.glsl"
#include "traverse/gl_ray_tracer.h"
#include "voxelize/gpu_grid.h"
#include "voxelize/sparse_octree.h"
#include "voxelize/value_textures.h"

namespace vgi {

const char* coneRadianceName(ConeRadiance r) {
  switch (r) {
    case ConeRadiance::Inject:
      return "inject";
    case ConeRadiance::Texels:
      return "texels";
    case ConeRadiance::Atlas:
      return "atlas";
    case ConeRadiance::None:
      return "none";
  }
  return "none";
}

ConeRadiance coneRadianceOf(const std::string& name) {
  for (ConeRadiance r : {ConeRadiance::Inject, ConeRadiance::Texels, ConeRadiance::Atlas, ConeRadiance::None})
    if (name == coneRadianceName(r)) return r;
  fail("internal: no cone radiance '", name, "'");
}

nlohmann::json ConeVolumeNeed::key() const {
  nlohmann::json k = {
      {"grid", grid.key()}, {"radiance", coneRadianceName(radiance)}, {"anisotropic", anisotropic}};
  if (directional)
    k["directional"] = directionalChain ? "level1" : "level0";  // (absent when none: earlier keys stand)
  return k;
}

nlohmann::json ConeVolumeNeed::settings() const {
  return {{"light_maps", lightMaps ? lightMaps->key() : nlohmann::json(nullptr)},
          {"bias", bias},
          {"normal_offset", normalOffset},
          {"inject_small", injectSmall}};
}

ValueGridNeed ConeVolumeNeed::valueGrids() const {
  return {grid, anisotropic ? ValueMips::Anisotropic : ValueMips::Isotropic, lightMaps};
}

namespace {
bool sameLights(const std::vector<Light>& a, const std::vector<Light>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].type != b[i].type || a[i].position != b[i].position || a[i].direction != b[i].direction ||
        a[i].intensity != b[i].intensity || a[i].coneHalfAngleDeg != b[i].coneHalfAngleDeg ||
        a[i].falloff != b[i].falloff)
      return false;
  return true;
}

// Adds to `out` box b and what b shadows from each light within the grid box [lo, hi]: b's corners
// carried away from the light to the grid's faces. False where a light lies within b (all of it).
bool addShadowed(Bounds& out, const Bounds& b, const std::vector<Light>& lights, glm::vec3 lo, glm::vec3 hi) {
  if (b.empty()) return true;
  out.extend(b.lo), out.extend(b.hi);
  for (const Light& l : lights) {
    const bool parallel = l.type == LightType::Directional;
    if (!parallel && glm::all(glm::greaterThanEqual(l.position, b.lo)) &&
        glm::all(glm::lessThanEqual(l.position, b.hi)))
      return false;
    for (int i = 0; i < 8; ++i) {
      const glm::vec3 c(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z);
      const glm::vec3 d = parallel ? l.direction : c - l.position;
      float t = 1e30f;  // to the grid's face the ray from c along d leaves through
      for (int a = 0; a < 3; ++a)
        if (d[a] > 1e-20f)
          t = std::min(t, std::max(hi[a] - c[a], 0.0f) / d[a]);
        else if (d[a] < -1e-20f)
          t = std::min(t, std::min(lo[a] - c[a], 0.0f) / d[a]);
      if (t < 1e29f) out.extend(c + t * d);
    }
  }
  return true;
}
}  // namespace

std::optional<CellRange> ConeVolume::changedCells(SceneResources& res, float before) const {
  const GridBox& box = own_->box();
  const glm::vec3 lo = box.origin, hi = box.origin + box.extent;
  Bounds changed;
  if (!addShadowed(changed, res.scene().dynamicBounds(before), res.lights(), lo, hi) ||
      !addShadowed(changed, res.scene().dynamicBounds(res.time()), res.lights(), lo, hi))
    return std::nullopt;
  if (changed.empty()) return CellRange{};
  // Two cells of margin: a (triangle, cell) pair is lit at the triangle's point nearest the cell's
  // centre, and the shadow test's bias and filter reach a little past the shadow's edge.
  return boundsCells(box, changed, 2, 3);
}

bool ConeVolume::update(SceneResources& res, const ResourceNeed& need, Profiler& prof) {
  need_ = need.spec<ConeVolumeNeed>();
  const glm::vec3 v = res.get<GridBox>(need_.grid).voxelSize();
  voxel_ = std::max({v.x, v.y, v.z});
  if (need_.radiance == ConeRadiance::Atlas) {  // the value grids are the volume, kept current as a resource
    volume_ = &res.get<ValueTextures>(need_.valueGrids());
    return res.changed(need_.valueGrids());
  }
  const bool lit = injectsRadiance(need_.radiance);
  const bool fresh = !own_;
  if (fresh) allocate(res);
  // With area lights the light maps follow the sample's lights: beginSample relights (injects).
  if (lit && res.sampleLights()) return false;
  if (!fresh && !res.changed(need_.pyramid()) && !(lit && res.changed(*need_.lightMaps)) &&
      filledFor_ == need_.settings().dump())
    return false;
  fill(res, prof);
  return true;
}

bool ConeVolume::relight(SceneResources& res, const ResourceNeed&, Profiler& prof) {
  if (!injectsRadiance(need_.radiance)) return false;
  fill(res, prof);
  return true;
}

void ConeVolume::allocate(SceneResources& res) {
  const GridBox& box = res.get<GridBox>(need_.grid);
  own_ = std::make_unique<ValueTextures>(box, std::vector<std::string>{"radiance"},
                                         need_.anisotropic ? ValueMips::Anisotropic : ValueMips::Isotropic);
  volume_ = own_.get();
  // A scene with dynamic meshes keeps each cell's largest pair: its frames inject only what moved.
  sums_.allocate(box.cellCount(), need_.directional,
                 need_.radiance == ConeRadiance::Inject && !res.scene().dynamicBounds(res.time()).empty());
  if (need_.directional) direction_ = makeGridTexture3D(box.resolution, 1, GL_RGBA8_SNORM, true);
}

void ConeVolume::fill(SceneResources& res, Profiler& prof) {
  ShaderLibrary& shaders = res.shaders();
  // A fill after the first (an animation's frame, a moved light, a sample's area lights) tries the
  // last fill's range: no pass for the maximum where it is the same (the sums are a fresh fill's).
  const bool again = !filledFor_.empty();
  const std::string settings = need_.settings().dump();
  const float rangeBefore = sums_.radianceMax();
  // Only the dynamic meshes moved (the settings, the lights and then the range as before): the sums
  // changed only where they were and are and in what they shadow, and only those cells are
  // resolved and filtered again.
  std::optional<CellRange> cells;
  if (again && settings == filledFor_ && sameLights(res.lights(), filledLights_))
    cells = changedCells(res, filledAt_);
  filledFor_ = settings;
  filledLights_ = res.lights();
  filledAt_ = res.time();
  if (injectsRadiance(need_.radiance))
    sums_.inject(res, res.get<GridBox>(need_.grid), need_.radiance, *need_.lightMaps, need_.bias,
                 need_.normalOffset, need_.injectSmall, nullptr, prof, again ? rangeBefore : 0.0f,
                 cells ? &*cells : nullptr);
  if (sums_.radianceMax() != rangeBefore) cells.reset();
  const unsigned words = res.get<GlPyramid>(need_.pyramid()).words();
  if (direction_) {
    auto s = prof.scope("vct_direction_resolve");
    const unsigned prog = shaders.program({"illum/vct/direction_resolve.comp.glsl"});
    glUseProgram(prog);
    const glm::uvec3 r = own_->box().resolution;
    const CellRange range = cells ? *cells : CellRange{{}, r};
    shaders.setUniform(prog, "uResolution", glm::uvec4(r, 0u));
    shaders.setUniform(prog, "uFirstCell", range.lo);
    shaders.setUniform(prog, "uEndCell", glm::min(range.hi, r));
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VALUE_DIRECTION, sums_.directions());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_PYRAMID, words);
    glBindImageTexture(IMAGE_VALUE_DIRECTION, direction_.get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA8_SNORM);
    const glm::uvec3 size = glm::max(range.hi, range.lo) - range.lo;
    if (range.count() > 0) glDispatchCompute((size.x + 3) / 4, (size.y + 3) / 4, (size.z + 3) / 4);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  }
  ValueSumBuffers b;
  b.counts = sums_.counts();
  b.sums[3] = sums_.sums();
  b.radianceMax = sums_.radianceMax();
  own_->resolve(b, shaders, prof, words, need_.directionalChain ? direction_.get() : 0u, cells);
}

void reduceCellMax(ShaderLibrary& shaders, unsigned cellMax, uint64_t cells, unsigned result) {
  if (cells > 0xffffffffull) fail("internal: reduceCellMax takes at most 2^32 - 1 cells");
  const unsigned reduce = shaders.program({"illum/vct/cell_max_reduce.comp.glsl"});
  glUseProgram(reduce);
  shaders.setUniform(reduce, "uCells", unsigned(cells));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_INJECT_CELL_MAX, cellMax);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VALUE_RADIANCE_MAX, result);
  // About 16 cells an invocation, in at most 65535 groups (GL's least limit) of 64.
  glDispatchCompute(unsigned(std::clamp<uint64_t>((cells + 64 * 16 - 1) / (64 * 16), 1, 65535)), 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void InjectionSums::allocate(uint64_t slots, bool directional, bool cellMax) {
  slots_ = std::max<uint64_t>(slots, 1);
  checkGpuAllocation(double(slots_) * ((directional ? 36.0 : 20.0) + (cellMax ? 4.0 : 0.0)),
                     "the radiance injection's sums (" + std::to_string(slots_) + " slots)");
  counts_ = makeBuffer(slots_ * 4);
  sums_ = makeBuffer(slots_ * 16);
  max_ = makeBuffer(4);
  directions_ = directional ? makeBuffer(slots_ * 16) : GlBuffer();
  cellMax_ = cellMax ? makeBuffer(slots_ * 4) : GlBuffer();
  const uint32_t zero = 0;
  for (unsigned b : {counts_.get(), sums_.get(), directions_.get(), cellMax_.get()})
    if (b) glClearNamedBufferData(b, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

float InjectionSums::inject(SceneResources& res, const GridBox& box, ConeRadiance radiance,
                            const LightMapNeed& mapsNeed, float bias, float normalOffset, int smallCells,
                            const SparseVoxelOctree* octree, Profiler& prof, float reuseRange,
                            const CellRange* region) {
  const unsigned counts = counts_.get(), sums = sums_.get(), max = max_.get(), directions = directions_.get(),
                 cellMax = cellMax_.get();
  const uint32_t zero = 0;
  const bool texels = radiance == ConeRadiance::Texels;
  if (cellMax && (texels || octree))
    fail("internal: the per-cell maxima are the dense volume's, radiance=inject");
  if (!(reuseRange > 0.0f && cellMax)) region = nullptr;
  auto clearAll = [&] {
    for (unsigned b : {counts, sums, directions, cellMax})
      if (b) glClearNamedBufferData(b, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  };
  if (!region) clearAll();
  injected_ = region ? region->count() : slots_;
  ShaderLibrary& shaders = res.shaders();
  const GpuScene& gpu = res.get<GpuScene>();
  const LightMaps& maps = res.get<LightMaps>(mapsNeed);
  const std::vector<std::string> files =
      texels ? std::vector<std::string>{"illum/vct/inject_texels.comp.glsl"}
             : std::vector<std::string>{"voxelize/conservative.vert.glsl", "voxelize/conservative.geom.glsl",
                                        "illum/vct/inject.frag.glsl"};
  ShaderDefines defs;
  if (!texels) defs["CONSERVATIVE_VALUES"] = defs["INJECT_HYBRID"] = "1";
  if (octree) defs["INJECT_SVO"] = "1";
  if (directions) {
    if (texels || octree) fail("internal: directional injection is the dense volume's, radiance=inject");
    defs["INJECT_DIRECTIONAL"] = "1";
  }
  if (cellMax) defs["INJECT_CELL_MAX"] = "1";
  const unsigned prog = shaders.program(files, defs);
  ShaderDefines checkDefs = defs;
  checkDefs["INJECT_CHECK_RANGE"] = "1";
  const unsigned checkProg = shaders.program(files, checkDefs);
  ShaderDefines regionDefs = checkDefs;
  regionDefs["INJECT_REGION"] = "1";
  const unsigned regionProg = region ? shaders.program(files, regionDefs) : 0u;
  defs.erase("INJECT_CELL_MAX");
  defs["INJECT_MAX"] = "1";
  const unsigned maxProg = shaders.program(files, defs);
  auto run = [&](unsigned p) {
    setGridUniforms(shaders, p, box);
    if (octree && p != maxProg) octree->bind(shaders, p);
    auto bindAll = [&] {
      glUseProgram(p);
      maps.bind();
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VALUE_RADIANCE_MAX, max);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VALUE_COUNTS, counts);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VALUE_RADIANCE, sums);
      if (directions && p != maxProg)
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VALUE_DIRECTION, directions);
      if (cellMax && p != maxProg)
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_INJECT_CELL_MAX, cellMax);
    };
    if (texels) {
      const int r = maps.resolution();
      shaders.setUniform(p, "uMapResolution", r);
      bindAll();
      glDispatchCompute(unsigned(r + 7) / 8, unsigned(r + 7) / 8, unsigned(maps.faceCount()));
    } else {
      const int side = int(std::max({box.resolution.x, box.resolution.y, box.resolution.z}));
      shaders.setUniform(p, "uViewport", float(side));
      shaders.setUniform(p, "uShadowBias", bias);
      shaders.setUniform(p, "uNormalOffset", normalOffset);
      shaders.setUniform(p, "uInjectSmallCells", smallCells);
      drawWithoutAttachments(side, side, [&] {
        bindAll();
        gpu.bind(shaders, p);
        gpu.draw();
      });
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  };
  // The largest radiance of any (triangle, cell) pair or texel the last pass saw (1 where none: unlit,
  // the sums stay 0).
  auto passMax = [&] {
    uint32_t bits = 0;
    float m = 0.0f;
    glGetNamedBufferSubData(max, 0, 4, &bits);
    std::memcpy(&m, &bits, 4);
    return m > 0.0f && std::isfinite(m) ? m : 1.0f;
  };
  glClearNamedBufferData(max, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  if (region) {
    const glm::uvec3 n = box.resolution;
    {
      auto s = prof.scope("vct_inject");
      // The region's sums from 0, then its pairs with the last fill's range.
      ShaderDefines clearDefs;
      if (directions) clearDefs["INJECT_DIRECTIONAL"] = "1";
      const unsigned clear = shaders.program({"illum/vct/inject_clear.comp.glsl"}, clearDefs);
      glUseProgram(clear);
      shaders.setUniform(clear, "uResolution", glm::uvec4(n, 0u));
      shaders.setUniform(clear, "uFirstCell", region->lo);
      shaders.setUniform(clear, "uEndCell", glm::min(region->hi, n));
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VALUE_COUNTS, counts);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VALUE_RADIANCE, sums);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_INJECT_CELL_MAX, cellMax);
      if (directions) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VALUE_DIRECTION, directions);
      const glm::uvec3 size = glm::max(glm::min(region->hi, n), region->lo) - region->lo;
      if (region->count() > 0) glDispatchCompute((size.x + 3) / 4, (size.y + 3) / 4, (size.z + 3) / 4);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
      shaders.setUniform(regionProg, "uRadianceMax", reuseRange);
      shaders.setUniform(regionProg, "uRegionLo", region->lo);
      shaders.setUniform(regionProg, "uRegionHi", glm::min(region->hi, n));
      if (region->count() > 0) run(regionProg);
    }
    {
      // This frame's range: the largest pair of any cell (the region's new, the rest as before).
      auto s = prof.scope("vct_inject_range");
      reduceCellMax(shaders, cellMax, slots_, max);
    }
    const float m = passMax();
    if (m == reuseRange) {
      radianceMax_ = m;
      return m;
    }
    clearAll();
    injected_ = slots_;
    auto s = prof.scope("vct_inject_again");
    shaders.setUniform(prog, "uRadianceMax", m);
    run(prog);
    radianceMax_ = m;
    return m;
  }
  if (reuseRange > 0.0f) {
    {
      auto s = prof.scope("vct_inject");
      shaders.setUniform(checkProg, "uRadianceMax", reuseRange);
      run(checkProg);
    }
    const float m = passMax();
    if (m == reuseRange) {  // this fill's own maximum: the sums a fresh fill makes
      radianceMax_ = m;
      return m;
    }
    // Another maximum (clamped, or a coarser range than a fresh fill's): the sums again with it.
    clearAll();
    auto s = prof.scope("vct_inject_again");
    shaders.setUniform(prog, "uRadianceMax", m);
    run(prog);
    radianceMax_ = m;
    return m;
  }
  float radianceMax = 1.0f;
  {
    // Pass 1: the largest radiance of any (triangle, cell) pair or texel: the fixed-point range.
    auto s = prof.scope("vct_inject_max");
    run(maxProg);
    radianceMax = passMax();
  }
  auto s = prof.scope("vct_inject");
  shaders.setUniform(prog, "uRadianceMax", radianceMax);
  run(prog);
  radianceMax_ = radianceMax;
  return radianceMax;
}

nlohmann::json ConeVolume::stats() {
  nlohmann::json j = volume_->describe();
  j["storage"] = "dense";
  if (own_) {
    // The injection's sums and counts per cell are the volume's too (20 bytes a cell).
    j["injection_bytes"] = sums_.bytes();
    j["bytes"] = j["bytes"].get<double>() + sums_.bytes();
    if (injectsRadiance(need_.radiance)) j["injected_cells"] = sums_.injectedSlots();
  }
  j["radiance_source"] = coneRadianceName(need_.radiance);
  j["directional"] = !need_.directional ? "none" : need_.directionalChain ? "level1" : "level0";
  if (direction_) j["bytes"] = j["bytes"].get<double>() + double(own_->box().cellCount()) * 4.0;
  if (injectsRadiance(need_.radiance)) j["radiance_max"] = sums_.radianceMax();
  return j;
}

void bindConeVolume(const ValueTextures& t, ShaderLibrary& shaders, unsigned prog, float step) {
  t.bind();
  if (t.mips() == ValueMips::Anisotropic) t.bindAniso("radiance");
  setGridUniforms(shaders, prog, t.box());
  const glm::vec3 v = t.box().voxelSize();
  shaders.setUniform(prog, "uVoxelSize", std::max({v.x, v.y, v.z}));
  shaders.setUniform(prog, "uMaxLod", float(t.levels() - 1));
  shaders.setUniform(prog, "uConeStep", step);
}

void ConeVolume::bind(ShaderLibrary& shaders, unsigned prog, float step) const {
  bindConeVolume(*volume_, shaders, prog, step);
  if (direction_) glBindTextureUnit(TEXUNIT_VALUE_DIRECTION, direction_.get());
}

ResourceKind coneVolumeKind() {
  return {"cone_volume",
          "the cone tracers' pre-integrated radiance/opacity volume with its (anisotropic) mips",
          [](const ResourceNeed& n) {
            const ConeVolumeNeed& c = n.spec<ConeVolumeNeed>();
            std::vector<ResourceNeed> d{c.pyramid()};
            if (injectsRadiance(c.radiance)) d.push_back(*c.lightMaps);
            if (c.radiance == ConeRadiance::Atlas) d.push_back(c.valueGrids());
            return d;
          },
          [](const ResourceNeed& n, const SceneNeeds&, const std::string& method, bool gl) {
            const ConeVolumeNeed& c = n.spec<ConeVolumeNeed>();
            requireGl(n, method, gl);
            if (c.radiance != ConeRadiance::None && !c.lightMaps)
              fail("method '", method,
                   "' asks for a cone volume with radiance=", coneRadianceName(c.radiance),
                   " without light maps");
          },
          [](const ResourceNeed& n) {
            // With radiance=atlas the value grids are the volume: nothing of its own.
            return n.spec<ConeVolumeNeed>().radiance == ConeRadiance::Atlas
                       ? std::vector<std::string>{}
                       : std::vector<std::string>{"cone_volume"};
          },
          [](const ResourceNeed& n, SceneResources&) -> std::unique_ptr<Resource> {
            return std::make_unique<ConeVolume>(n.spec<ConeVolumeNeed>());
          },
          "volume"};
}

const ResourceKind& ConeVolumeNeed::row() {
  static const ResourceKind k = coneVolumeKind();
  return k;
}

}  // namespace vgi
