// Multi-valued grids as 3D textures (voxelize/value_textures.h) on llvmpipe:
// the GPU resolve against the CPU decode of the same sums, the GPU mip levels
// against the C++ builders of the same kernels, and the GLSL lookups
// (shaders/shared/value_textures.glsl) against the same coordinates in C++.
#include "voxelize/value_textures.h"

#include <glad/gl.h>

#include <fstream>
#include <glm/gtc/packing.hpp>
#include <random>

#include "core/gl_context.h"
#include "core/profiler.h"
#include "core/scene_loader.h"
#include "core/shader_library.h"
#include "illum/framework/resources.h"
#include "illum/resources/or_mip_pyramid.h"
#include "illum/resources/value_grids.h"
#include "shaders/shared/bindings.glsl"
#include "shaders/shared/value_grid.glsl"
#include "test_util.h"
#include "voxelize/atlas_voxelizer.h"
#include "voxelize/gpu_grid.h"

namespace vgi {

namespace {

// Half-float texels against the CPU (test_util.h).
using test::compareHalf;
using test::halfStep;
using test::toHalf;

struct ValueFixture {
  std::unique_ptr<GlContext> gl = GlContext::create();
  ShaderLibrary shaders;
  Scene scene;
  Profiler prof{true};
  std::unique_ptr<AtlasVoxelizer> atlas;
  std::unique_ptr<ValueTextures> tex;
  explicit ValueFixture(glm::uvec3 res, ValueMips mips) {
    const std::string path = testing::TempDir() + "/value_textures.json";
    std::ofstream(path) << R"({ "meshes": [ {"path": "builtin:cornell"} ],
        "materials": { "white": {"albedo": [0.5, 0.5, 0.5], "ks": [0.3, 0.2, 0.1], "exponent": 50} } })";
    scene = loadScene(path);
    VoxelizeRequest r;
    r.scene = &scene;
    r.box = fitGridBox(scene, res, 0.0f);
    r.gl = gl.get();
    r.shaders = &shaders;
    r.valueGrids = {"normal", "albedo", "glossy"};
    atlas = std::make_unique<AtlasVoxelizer>(r, prof);
    atlas->voxelizeFrame(0.0f, prof);
    tex = std::make_unique<ValueTextures>(r.box, r.valueGrids, mips);
    tex->resolve(atlas->valueBuffers(), shaders, prof);
  }
};

}  // namespace

TEST(ValueTextures, GpuResolveEqualsTheCpuDecodeOfTheSameSums) {
  ValueFixture s({64, 48, 128}, ValueMips::None);
  const ValueGrids cpu = s.atlas->readValues();
  // Counts: integers, bit for bit; occupancy exactly 0 or 1.
  EXPECT_EQ(s.tex->readCounts(), cpu.counts);
  const std::vector<glm::vec4> occ = s.tex->read("occupancy");
  size_t occupied = 0;
  for (size_t i = 0; i < occ.size(); ++i) {
    ASSERT_EQ(occ[i].x, cpu.counts[i] > 0 ? 1.0f : 0.0f) << i;
    occupied += cpu.counts[i] > 0;
  }
  EXPECT_GT(occupied, 1000u);
  // Means: the CPU decode's floats in the texture's format (half: one step; 8-bit: ½ step).
  for (const char* ch : {"normal", "albedo", "glossy"}) {
    const std::vector<glm::vec4> gpu = s.tex->read(ch);
    const std::vector<glm::vec4>& want = cpu.channel(ch);
    int bad = 0;
    for (size_t i = 0; i < gpu.size(); ++i) {
      glm::vec4 w = want[i];
      if (std::string(ch) == "glossy" && cpu.counts[i])
        w.w = shared::encodeExponent(w.w);  // the texture keeps the code
      for (int c = 0; c < 4; ++c) {
        const bool albedo = std::string(ch) == "albedo";
        const float expect = albedo ? std::round(w[c] * 255.0f) / 255.0f : toHalf(w[c]);
        // The glossy code went through exp2/log2 on the CPU side: allow its float rounding too.
        const float tol = albedo ? 0.51f / 255.0f : halfStep(w[c]) * (c == 3 ? 2.0f : 1.0f);
        if (c == 3 && std::string(ch) != "glossy") {
          bad += gpu[i][c] != 0.0f;
          continue;
        }
        if (std::abs(gpu[i][c] - expect) > tol && bad++ < 5)
          ADD_FAILURE() << ch << " cell " << i << " c" << c << ": " << gpu[i][c] << " vs " << expect;
      }
    }
    EXPECT_EQ(bad, 0) << ch;
  }
  EXPECT_EQ(s.gl->errorCount(), 0);
}

TEST(ValueTextures, GpuMipLevelsEqualTheCppBuildersOfTheSameKernels) {
  ValueFixture s({64, 48, 128}, ValueMips::Anisotropic);
  EXPECT_EQ(s.tex->levels(), 8);  // 128 → 1 along the longest axis
  // Isotropic: each level from the GPU's level below, through isoMipLevel.
  for (int l = 1; l < s.tex->levels(); ++l) {
    const std::vector<glm::vec4> below = s.tex->read("normal", l - 1);
    compareHalf(s.tex->read("normal", l), isoMipLevel(below, s.tex->levelSize(l - 1)),
                ("normal level " + std::to_string(l)).c_str());
  }
  // The occupancy chain (R8: 1/255 steps) is the mean fill of each block.
  const std::vector<glm::vec4> occ1 = s.tex->read("occupancy", 1);
  const std::vector<glm::vec4> occ1Cpu = isoMipLevel(s.tex->read("occupancy", 0), s.tex->levelSize(0));
  for (size_t i = 0; i < occ1.size(); ++i) ASSERT_NEAR(occ1[i].x, occ1Cpu[i].x, 0.51f / 255.0f) << i;
  // Anisotropic: the grid's level 1 from (albedo rgb, occupancy), level 2 from level 1, each face.
  std::vector<glm::vec4> base = s.tex->read("albedo", 0);
  const std::vector<glm::vec4> occ0 = s.tex->read("occupancy", 0);
  for (size_t i = 0; i < base.size(); ++i) base[i].w = occ0[i].x;
  for (uint32_t f = 0; f < 6; ++f) {
    const std::vector<glm::vec4> l1 = s.tex->readAniso("albedo", int(f), 1);
    compareHalf(l1, anisoMipLevel(base, s.tex->levelSize(0), f),
                ("albedo aniso level 1 face " + std::to_string(f)).c_str());
    compareHalf(s.tex->readAniso("albedo", int(f), 2), anisoMipLevel(l1, s.tex->levelSize(1), f),
                ("albedo aniso level 2 face " + std::to_string(f)).c_str());
  }
  test::expectError([&] { s.tex->bindAniso("glossy"); }, {"glossy", "anisotropic"});
  EXPECT_EQ(s.gl->errorCount(), 0);
}

// Front-to-back composition: a full front child hides what is behind it, an
// empty one shows it; the opposite direction sees the other child.
TEST(ValueTextures, AnisotropicReduceComposesFrontToBack) {
  glm::vec4 c[8];
  for (auto& v : c) v = glm::vec4(0.0f);
  c[0] = glm::vec4(1, 0, 0, 1);                                            // x = 0: opaque red
  c[1] = glm::vec4(0, 1, 0, 1);                                            // x = 1: opaque green
  EXPECT_EQ(shared::anisoReduce(c, 0), glm::vec4(0.25f, 0, 0, 0.25f));     // travelling +x meets red first
  EXPECT_EQ(shared::anisoReduce(c, 1), glm::vec4(0, 0.25f, 0, 0.25f));     // −x meets green
  EXPECT_EQ(shared::anisoReduce(c, 2), glm::vec4(0.25f, 0.25f, 0, 0.5f));  // ±y: side by side, both seen
  const glm::vec3 d = glm::normalize(glm::vec3(1, -2, 2));
  const glm::vec3 w = shared::anisoWeights(d);
  EXPECT_NEAR(w.x + w.y + w.z, 1.0f, 1e-6f);
  EXPECT_EQ(shared::anisoFaces(d), glm::uvec3(0, 3, 4));
}

TEST(ValueTextures, GlslLookupsMatchTheSharedCoordinatesInCpp) {
  ValueFixture s({64, 48, 128}, ValueMips::Anisotropic);
  const GridBox& box = s.tex->box();
  const glm::uvec3 r = box.resolution;
  const std::vector<uint32_t> counts = s.tex->readCounts();
  const std::vector<glm::vec4> normal0 = s.tex->read("normal", 0), albedo0 = s.tex->read("albedo", 0),
                               occ0 = s.tex->read("occupancy", 0);
  const shared::GridParams g = box.params();
  // Points: cell centres (exact texels at lod 0) and random points (trilinear).
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<glm::vec4> points;
  std::vector<glm::uvec3> cells;
  for (int i = 0; i < 256; ++i) {
    glm::uvec3 c(rng() % r.x, rng() % r.y, rng() % r.z);
    if (i % 2 == 0) c = glm::uvec3(rng() % r.x, 0, rng() % r.z);  // the floor: occupied cells
    cells.push_back(c);
    glm::vec3 q = glm::vec3(c) + 0.5f;
    glm::vec3 p = box.origin + box.axes[0] * (q.x / g.axisX.w) + box.axes[1] * (q.y / g.axisY.w) +
                  box.axes[2] * (q.z / g.axisZ.w);
    points.push_back(glm::vec4(p, 0.0f));
  }
  const size_t centres = points.size();
  for (int i = 0; i < 256; ++i) {
    glm::vec3 q(u(rng) * r.x, u(rng) * r.y, u(rng) * r.z);
    glm::vec3 p = box.origin + box.axes[0] * (q.x / g.axisX.w) + box.axes[1] * (q.y / g.axisY.w) +
                  box.axes[2] * (q.z / g.axisZ.w);
    points.push_back(glm::vec4(p, i % 2 ? 1.5f : 0.0f));
  }
  const unsigned prog = s.shaders.program({"../tests/data/shaders/value_probe.comp.glsl"});
  unsigned bufs[2];
  glCreateBuffers(2, bufs);
  glNamedBufferStorage(bufs[0], GLsizeiptr(points.size() * sizeof(glm::vec4)), points.data(), 0);
  glNamedBufferStorage(bufs[1], GLsizeiptr(points.size() * 4 * sizeof(glm::vec4)), nullptr, 0);
  glUseProgram(prog);
  setGridUniforms(s.shaders, prog, box);
  s.shaders.setUniform(prog, "uCount", int(points.size()));
  const glm::vec3 dir = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
  s.shaders.setUniform(prog, "uDirection", dir);
  s.tex->bind();
  s.tex->bindAniso("normal");
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_TRACE_RAYS, bufs[0]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_TRACE_HITS, bufs[1]);
  glDispatchCompute(unsigned(points.size() + 63) / 64, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<glm::vec4> res(points.size() * 4);
  glGetNamedBufferSubData(bufs[1], 0, GLsizeiptr(res.size() * sizeof(glm::vec4)), res.data());
  glDeleteBuffers(2, bufs);
  // Cell centres at lod 0: the texels themselves (within the filter's rounding
  // off the exact centre: below 1/256 of a neighbour), so valueUvw lands in the right cell.
  int occupied = 0;
  for (size_t i = 0; i < centres; ++i) {
    const size_t c = (size_t(cells[i].z) * r.y + cells[i].y) * r.x + cells[i].x;
    ASSERT_EQ(res[4 * i].y, float(counts[c])) << i;
    ASSERT_NEAR(res[4 * i].x, occ0[c].x, 2e-3f) << i;
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(res[4 * i + 1][k], normal0[c][k], 2e-3f) << i;
    if (counts[c]) {
      ++occupied;
      for (int k = 0; k < 3; ++k) ASSERT_NEAR(res[4 * i + 2][k], albedo0[c][k], 2e-3f) << i;
    }
  }
  EXPECT_GT(occupied, 64);
  // Random points: GL's trilinear filter (llvmpipe weights in 1/256 steps)
  // against the same filter in C++ on the read-back texels.
  auto trilinear = [&](const std::vector<glm::vec4>& t, glm::uvec3 size, glm::vec3 uvw) {
    glm::vec3 x = uvw * glm::vec3(size) - 0.5f;
    glm::ivec3 i0 = glm::ivec3(glm::floor(x));
    glm::vec3 f = x - glm::vec3(i0);
    glm::vec4 sum(0.0f);
    for (int k = 0; k < 8; ++k) {
      glm::ivec3 p = i0 + glm::ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
      float w = (k & 1 ? f.x : 1 - f.x) * (k & 2 ? f.y : 1 - f.y) * (k & 4 ? f.z : 1 - f.z);
      if (glm::any(glm::lessThan(p, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(p, glm::ivec3(size))))
        continue;
      sum += w * t[(size_t(p.z) * size.y + p.y) * size.x + p.x];
    }
    return sum;
  };
  for (size_t i = centres; i < points.size(); ++i) {
    if (points[i].w != 0.0f) continue;
    const glm::vec3 uvw = shared::valueUvw(g, glm::vec3(points[i]));
    EXPECT_NEAR(res[4 * i].x, trilinear(occ0, r, uvw).x, 1.5e-2f) << i;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(res[4 * i + 1][k], trilinear(normal0, r, uvw)[k], 1.5e-2f) << i;
  }
  // Anisotropic lookups along dir at the grid's level 1.5 mix faces by d²:
  // non-negative alpha up to 1, and a floor region (occupied below) seen.
  float maxAlpha = 0;
  for (size_t i = centres; i < points.size(); ++i)
    if (points[i].w > 0.0f) {
      ASSERT_GE(res[4 * i + 3].w, 0.0f);
      ASSERT_LE(res[4 * i + 3].w, 1.0f + 1e-3f);
      maxAlpha = std::max(maxAlpha, res[4 * i + 3].w);
    }
  EXPECT_GT(maxAlpha, 0.0f);
  EXPECT_EQ(s.gl->errorCount(), 0);
}

// Through the framework: a method that declares value grids gets them built
// (and named in `built`), and bad declarations are refused with the reason.
TEST(ValueTextures, SceneResourcesBuildThemOnlyWithTheAtlasGrid) {
  std::unique_ptr<GlContext> gl = GlContext::create();
  ShaderLibrary shaders;
  const Scene scene = loadScene("builtin:cornell");
  BinaryGridNeed grid;
  grid.resolution = {64, 64, 128};
  grid.values = {"normal", "albedo"};
  SceneNeeds n;
  n.add(OrMipPyramidNeed{grid});
  n.add(ValueGridNeed{grid, ValueMips::Isotropic, std::nullopt});
  n.check("test", true);
  SceneResources res(scene, n, gl.get(), &shaders, {0.0f}, 0);
  Profiler prof(true);
  res.update(0.0f, prof);
  const std::vector<std::string> built = res.built();
  EXPECT_EQ(built, (std::vector<std::string>{"binary_grid", "or_mip_pyramid", "value_grids", "value_mips"}));
  EXPECT_EQ(built, n.names());
  EXPECT_EQ(res.get<ValueTextures>().levels(), 8);
  nlohmann::json stats;
  res.addStats(stats);
  EXPECT_EQ(stats["value_grids"]["channels"].size(), 2u) << stats.dump();
  EXPECT_GT(stats["grid"]["voxels_set"].get<long>(), 0);
  auto with = [&](const BinaryGridNeed& g) {
    SceneNeeds m;
    m.add(ValueGridNeed{g, ValueMips::None, std::nullopt});
    return m;
  };
  BinaryGridNeed exact = grid;
  exact.voxelizer = "exact";
  test::expectError([&] { with(exact).check("m", true); }, {"m", "atlas", "voxelizer=exact"});
  test::expectError([&] { n.check("m", false); }, {"m", "CPU"});
  BinaryGridNeed speed = grid;
  speed.values = {"speed"};
  test::expectError([&] { with(speed).check("m", true); }, {"speed"});
  EXPECT_EQ(gl->errorCount(), 0);
}

}  // namespace vgi

namespace vgi {

// The radiance channel (VGI §3, Table 2): a Lambert floor (ρ = 0.5) under a
// point light, with a floating quad whose shadow falls on the floor's edge.
// Each floor cell holds the mean diffuse direct radiance of its points:
// ρ/π·I·cos θ/d² averaged over the cell, and 0 in the shadow.
TEST(ValueTextures, RadianceChannelIsTheDirectLightOfEachCell) {
  std::unique_ptr<GlContext> gl = GlContext::create();
  ShaderLibrary shaders;
  Scene s;
  test::addFloor(s, 1.0f, 0.0f, test::addMaterial(s, glm::vec3(0.5f)));
  Mesh occ;
  occ.name = "occluder";
  occ.source = "test";
  occ.positions = {{0.4f, 0.25f, -0.2f}, {0.8f, 0.25f, -0.2f}, {0.8f, 0.25f, 0.2f}, {0.4f, 0.25f, 0.2f}};
  occ.triangles = {{0, 2, 1}, {0, 3, 2}};
  occ.material = test::addMaterial(s, glm::vec3(0.5f));
  s.meshes.push_back(occ);
  Light l;
  l.type = LightType::Point;
  l.position = {0.0f, 0.5f, 0.0f};
  l.intensity = glm::vec3(1.0f);
  s.lights = {l};
  BinaryGridNeed grid;
  grid.resolution = {64, 64, 128};
  grid.values = {"albedo", "radiance"};
  SceneNeeds n;
  n.add(OrMipPyramidNeed{grid});
  n.add(ValueGridNeed{grid, ValueMips::None, LightMapNeed{1024, false}});
  n.check("test", true);
  SceneNeeds noMaps;
  noMaps.add(ValueGridNeed{grid, ValueMips::None, std::nullopt});
  test::expectError([&] { noMaps.check("m", true); }, {"m", "radiance", "light maps"});
  SceneResources res(s, n, gl.get(), &shaders, {0.0f}, 0);
  Profiler prof(true);
  res.update(0.0f, prof);
  const ValueTextures& tex = res.get<ValueTextures>();
  const std::vector<glm::vec4> rad = tex.read("radiance");
  const std::vector<uint32_t> counts = tex.readCounts();
  const GridBox& box = tex.box();
  const glm::uvec3 r = box.resolution;
  const glm::vec3 cell = box.voxelSize();
  int lit = 0, shadowed = 0;
  for (uint32_t z = 0; z < r.z; z += 3)
    for (uint32_t x = 0; x < r.x; x += 3) {
      const size_t i = (size_t(z) * r.y + 0) * r.x + x;  // y = 0: the floor's cells
      if (!counts[i]) continue;
      const glm::vec3 lo = box.origin + glm::vec3(x, 0, z) * cell;
      // The cell's floor area, 8×8 sub-samples; a cell half in shadow is skipped.
      double expected = 0;
      int inShadow = 0;
      for (int b = 0; b < 8; ++b)
        for (int a = 0; a < 8; ++a) {
          const glm::vec3 p(lo.x + (a + 0.5f) / 8 * cell.x, 0.0f, lo.z + (b + 0.5f) / 8 * cell.z);
          const glm::vec3 d = l.position - p;
          const float d2 = glm::dot(d, d), cosT = d.y / std::sqrt(d2);
          // The ray to the light crosses y = 0.25 halfway up: inside the occluder?
          const glm::vec3 m = 0.5f * (p + l.position);
          const bool blocked = m.x > 0.4f && m.x < 0.8f && std::abs(m.z) < 0.2f;
          inShadow += blocked;
          expected += blocked ? 0.0 : 0.5 / M_PI * cosT / d2 / 64.0;
        }
      if (inShadow == 64) {
        EXPECT_LT(rad[i].x, 1e-3f) << x << "," << z;
        ++shadowed;
      } else if (inShadow == 0) {
        EXPECT_NEAR(rad[i].x, expected, 0.03 * expected) << x << "," << z;
        EXPECT_EQ(rad[i].x, rad[i].z) << x << "," << z;  // a white light on grey: equal channels
        ++lit;
      }
    }
  EXPECT_GT(lit, 200);
  EXPECT_GT(shadowed, 3);
  nlohmann::json stats;
  res.addStats(stats);
  EXPECT_TRUE(stats["grid"]["stats"].contains("radiance_max")) << stats.dump();
  EXPECT_EQ(gl->errorCount(), 0);
}

}  // namespace vgi
