// Voxel cone tracing (illum/methods/vct.cpp, illum/methods/vct_ao.cpp, illum/kits/cone_kit.h,
// shaders/illum/vct/cones.glsl): the volume's pre-integration on the GPU
// against the C++ builders of the same kernels, a single opaque cell seen
// along each axis, the cone march through a uniform medium against the closed
// form, AO of an open plane and under a parallel plane, finite results at
// grazing normals and for cones leaving the grid, the constellations' weights,
// and bad parameters. The point-lit sphere is in analytic_sphere_test.cpp.
#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <glm/gtc/packing.hpp>
#include <random>

#include "cone_fixture.h"
#include "core/gl_context.h"
#include "core/image_metrics.h"
#include "core/profiler.h"
#include "core/shader_library.h"
#include "illum/kits/cone_kit.h"
#include "illum/run/render_job.h"
#include "render_util.h"
#include "shaders/shared/bindings.glsl"
#include "shaders/shared/value_grid.glsl"
#include "test_util.h"
#include "traverse/gl_ray_tracer.h"
#include "voxelize/value_textures.h"

namespace vgi {

namespace {

using test::compareHalf;
using test::halfStep;
using test::toHalf;
using test::unitBox;
using test::VolumeFixture;

}  // namespace

// Level 0 is (mean radiance, 1) where the grid's bit is set and the cell was
// lit, (0, 0, 0, 1) where set and never injected, 0 elsewhere; every level
// above, isotropic and each anisotropic face, equals the C++ builder applied
// to the GPU's level below (GPU == CPU up to a half-float step).
TEST(ConeVolume, PreIntegrationOnTheGpuEqualsTheCppBuilders) {
  const GridBox box = unitBox({32, 16, 128});
  BinaryGrid grid(box);
  const size_t cells = box.cellCount();
  std::vector<uint32_t> counts(cells, 0), sums(cells * 4, 0);
  std::mt19937 rng(5);
  const float radianceMax = 2.0f;
  for (uint32_t z = 0; z < box.resolution.z; ++z)
    for (uint32_t y = 0; y < box.resolution.y; ++y)
      for (uint32_t x = 0; x < box.resolution.x; ++x) {
        const size_t i = (size_t(z) * box.resolution.y + y) * box.resolution.x + x;
        if (rng() % 3 == 0) grid.set(x, y, z);
        counts[i] = rng() % 4;  // some set cells without injected light, some lit cells without the bit
        for (uint32_t k = 0; k < 3 && counts[i]; ++k)
          sums[i * 4 + k] = counts[i] * shared::toFixedRadiance(float(rng() % 1000) / 500.0f, radianceMax);
      }
  for (ValueMips mips : {ValueMips::Isotropic, ValueMips::Anisotropic}) {
    VolumeFixture v(box, mips, grid, counts, sums, radianceMax);
    std::vector<glm::vec4> want(cells, glm::vec4(0.0f));
    for (uint32_t z = 0; z < box.resolution.z; ++z)
      for (uint32_t y = 0; y < box.resolution.y; ++y)
        for (uint32_t x = 0; x < box.resolution.x; ++x) {
          const size_t i = (size_t(z) * box.resolution.y + y) * box.resolution.x + x;
          if (!grid.test(x, y, z)) continue;
          want[i] = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
          if (counts[i])
            want[i] += shared::decodeRadianceMean(
                glm::uvec4(sums[i * 4], sums[i * 4 + 1], sums[i * 4 + 2], 0u), counts[i], radianceMax);
        }
    const std::vector<glm::vec4> level0 = v.tex->read("radiance", 0);
    compareHalf(level0, want, "level 0");
    for (int l = 1; l < v.tex->levels(); ++l)
      compareHalf(v.tex->read("radiance", l),
                  isoMipLevel(v.tex->read("radiance", l - 1), v.tex->levelSize(l - 1)),
                  "isotropic level " + std::to_string(l));
    if (mips == ValueMips::Anisotropic)
      for (uint32_t f = 0; f < 6; ++f) {
        const std::vector<glm::vec4> l1 = v.tex->readAniso("radiance", int(f), 1);
        compareHalf(l1, anisoMipLevel(level0, v.tex->levelSize(0), f),
                    "aniso level 1 face " + std::to_string(f));
        compareHalf(v.tex->readAniso("radiance", int(f), 2), anisoMipLevel(l1, v.tex->levelSize(1), f),
                    "aniso level 2 face " + std::to_string(f));
      }
    EXPECT_EQ(v.gl->errorCount(), 0);
  }
}

// vct's directional=level1: with a level-0 direction texture D the anisotropic
// chain's first level sees each cell's radiance from the side the face's cones
// come from — the C++ builder on level 0 with every cell's rgb times
// directionalFacing(−travel, D) (GPU == CPU up to a half-float step); the
// levels above and the isotropic chain are built as before.
TEST(ConeVolume, DirectionalFirstLevelEqualsTheCppBuilder) {
  const GridBox box = unitBox({32, 16, 128});
  BinaryGrid grid(box);
  const size_t cells = box.cellCount();
  std::vector<uint32_t> counts(cells, 0), sums(cells * 4, 0);
  std::vector<glm::vec4> directions(cells, glm::vec4(0.0f));
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const float radianceMax = 2.0f;
  for (size_t i = 0; i < cells; ++i) {
    grid.set(uint32_t(i % box.resolution.x), uint32_t(i / box.resolution.x % box.resolution.y),
             uint32_t(i / (size_t(box.resolution.x) * box.resolution.y)));
    counts[i] = 1 + rng() % 3;
    for (uint32_t k = 0; k < 3; ++k)
      sums[i * 4 + k] = counts[i] * shared::toFixedRadiance(float(rng() % 1000) / 500.0f, radianceMax);
    glm::vec3 d(u(rng), u(rng), u(rng));
    if (glm::length(d) > 1.0f) d = glm::normalize(d);
    directions[i] =
        glm::vec4(rng() % 4 == 0 ? glm::vec3(0.0f) : d, 0.0f);  // some cells lit alike on both sides
  }
  std::vector<glm::vec4> plainLevel0, plainLevel1[6];
  {
    VolumeFixture plain(box, ValueMips::Anisotropic, grid, counts, sums, radianceMax);
    plainLevel0 = plain.tex->read("radiance", 0);
    for (int f = 0; f < 6; ++f) plainLevel1[f] = plain.tex->readAniso("radiance", f, 1);
  }
  VolumeFixture v(box, ValueMips::Anisotropic, grid, counts, sums, radianceMax, &directions);
  std::vector<glm::vec4> stored(cells);  // D as the texture holds it (8-bit signed normalized)
  glGetTextureImage(v.direction.get(), 0, GL_RGBA, GL_FLOAT, GLsizei(cells * sizeof(glm::vec4)),
                    stored.data());
  const std::vector<glm::vec4> level0 = v.tex->read("radiance", 0);
  compareHalf(level0, plainLevel0, "level 0 is not directional");
  compareHalf(v.tex->read("radiance", 1), isoMipLevel(level0, v.tex->levelSize(0)), "isotropic level 1");
  double changed = 0.0;
  for (uint32_t f = 0; f < 6; ++f) {
    std::vector<glm::vec4> seen = level0;
    for (size_t i = 0; i < cells; ++i)
      seen[i] = glm::vec4(
          glm::vec3(seen[i]) * shared::directionalFacing(-shared::anisoFaceTravel(f), glm::vec3(stored[i])),
          seen[i].w);
    const std::vector<glm::vec4> l1 = v.tex->readAniso("radiance", int(f), 1);
    compareHalf(l1, anisoMipLevel(seen, v.tex->levelSize(0), f),
                "directional level 1 face " + std::to_string(f));
    compareHalf(v.tex->readAniso("radiance", int(f), 2), anisoMipLevel(l1, v.tex->levelSize(1), f),
                "directional level 2 face " + std::to_string(f));
    for (size_t i = 0; i < l1.size(); ++i) changed += std::abs(double(plainLevel1[f][i].x) - double(l1[i].x));
  }
  EXPECT_GT(changed, 1.0) << "the direction changed the first level";
  EXPECT_EQ(v.gl->errorCount(), 0);
}

// One lit opaque cell (radiance L) in an empty grid: in the anisotropic chain
// every face sees it with opacity 4^-l at level l (one of the block's four
// lines, composed with empty cells) and radiance L·4^-l; a thin cone through
// its centre along each of the six axis directions — in either chain —
// gathers L with opacity 1, and a cone beside it gathers nothing; degenerate
// cones (179.9° wide, zero length, outside the grid) stay finite.
TEST(ConeVolume, ASingleOpaqueCellSeenAlongEachAxis) {
  const GridBox box = unitBox({64, 64, 128});
  BinaryGrid grid(box);
  const glm::uvec3 c(21, 42, 77);
  grid.set(c.x, c.y, c.z);
  std::vector<uint32_t> counts(box.cellCount(), 0), sums(box.cellCount() * 4, 0);
  const size_t i = (size_t(c.z) * box.resolution.y + c.y) * box.resolution.x + c.x;
  const float radianceMax = 1.0f;
  const glm::vec3 L(0.8f, 0.4f, 0.2f);
  counts[i] = 1;
  for (int k = 0; k < 3; ++k) sums[i * 4 + k] = shared::toFixedRadiance(L[k], radianceMax);
  for (ValueMips mips : {ValueMips::Anisotropic, ValueMips::Isotropic}) {
    VolumeFixture v(box, mips, grid, counts, sums, radianceMax);
    if (mips == ValueMips::Anisotropic)
      for (int l = 1; l <= 3; ++l)
        for (int f = 0; f < 6; ++f) {
          const std::vector<glm::vec4> t = v.tex->readAniso("radiance", f, l);
          const glm::uvec3 s = v.tex->levelSize(l), p = c >> glm::uvec3(l);
          const glm::vec4 got = t[(size_t(p.z) * s.y + p.y) * s.x + p.x];
          const float a = std::pow(0.25f, float(l));
          EXPECT_NEAR(got.w, a, halfStep(a)) << "level " << l << " face " << f;
          EXPECT_NEAR(got.x, L.x * a, 4 * halfStep(L.x * a)) << "level " << l << " face " << f;
        }
    const glm::vec3 voxel = box.voxelSize();
    const glm::vec3 centre = box.origin + (glm::vec3(c) + 0.5f) * voxel;
    std::vector<ProbeCone> cones;
    for (int axis = 0; axis < 3; ++axis)
      for (float sign : {1.0f, -1.0f}) {
        glm::vec3 d(0.0f);
        d[axis] = sign;
        // Steps of a voxel, samples at the centres of the steps: the tenth sample is the cell's centre.
        cones.push_back({centre - d * (9.5f * voxel.x), d, 0.0f, 20.0f * voxel.x});
        cones.push_back({centre - d * (9.5f * voxel.x) + glm::vec3(d.y, d.z, d.x) * (3.0f * voxel.x), d, 0.0f,
                         20.0f * voxel.x});  // three cells beside it
      }
    // Degenerate cones: 179.9° wide, zero length, starting outside the grid, leaving it at once.
    const size_t axisCones = cones.size();
    for (float tanHalf : {0.0f, 1e3f})
      for (float length : {0.0f, 1e-9f, 5.0f})
        for (glm::vec3 apex : {centre, glm::vec3(-1.0f), glm::vec3(box.extent) * 0.999f})
          cones.push_back({apex, glm::normalize(glm::vec3(1.0f, 1e-7f, 0.0f)), tanHalf, length});
    const std::vector<ProbeResult> r = traceConesGl(*v.tex, v.shaders, cones, 1.0f, false);
    for (size_t k = axisCones; k < r.size(); ++k) {
      for (int c = 0; c < 4; ++c) {
        ASSERT_TRUE(std::isfinite(r[k].radianceOpacity[c])) << "degenerate cone " << k;
        ASSERT_TRUE(std::isfinite(r[k].occlusionEscapedSamples[c])) << "degenerate cone " << k;
      }
      EXPECT_GE(r[k].radianceOpacity.w, 0.0f);
      EXPECT_LE(r[k].radianceOpacity.w, 1.0f);
    }
    for (size_t k = 0; k < axisCones; k += 2) {
      const std::string what = std::string(mips == ValueMips::Anisotropic ? "anisotropic" : "isotropic") +
                               " direction " + std::to_string(k / 2);
      EXPECT_NEAR(r[k].radianceOpacity.w, 1.0f, 1e-3f) << what;
      EXPECT_NEAR(r[k].radianceOpacity.x, L.x, 2e-3f) << what;
      EXPECT_NEAR(r[k].radianceOpacity.z, L.z, 2e-3f) << what;
      EXPECT_EQ(r[k + 1].radianceOpacity.w, 0.0f) << what << " (beside)";
    }
    EXPECT_EQ(v.gl->errorCount(), 0);
  }
}

// A cone through a uniform medium of opacity α per voxel (each level-l cell
// 1 − (1 − α)^(2^l), as the anisotropic chain composes it) has the opacity
// 1 − (1 − α)^(length / voxel) whatever its aperture and step: the step
// correction of cones.glsl against the closed form.
TEST(ConeVolume, OpacityThroughAUniformMediumMatchesTheClosedForm) {
  const GridBox box = unitBox({128, 128, 128});
  BinaryGrid grid(box);
  std::vector<uint32_t> counts(box.cellCount(), 0), sums(box.cellCount() * 4, 0);
  VolumeFixture v(box, ValueMips::Anisotropic, grid, counts, sums, 1.0f);
  const float voxel = box.voxelSize().x;
  for (float alpha : {0.01f, 0.05f, 0.2f})
    for (float step : {0.3f, 1.0f, 2.5f}) {
      std::vector<ProbeCone> cones;
      for (float tanHalf : {0.0f, 0.05f, 0.3f, 1.0f})
        for (float length : {3.0f, 17.5f, 60.0f})
          cones.push_back({glm::vec3(0.1f, 0.2f, 0.15f), glm::normalize(glm::vec3(1.0f, 0.7f, 0.4f)), tanHalf,
                           length * voxel});
      const std::vector<ProbeResult> r = traceConesGl(*v.tex, v.shaders, cones, step, false, alpha);
      for (size_t k = 0; k < r.size(); ++k) {
        const float expected = 1.0f - std::pow(1.0f - alpha, cones[k].length / voxel);
        EXPECT_NEAR(r[k].radianceOpacity.w, expected, 2e-4f + 1e-3f * expected)
            << "alpha " << alpha << " step " << step << " tan " << cones[k].tanHalf << " length "
            << cones[k].length / voxel;
      }
    }
}

// Both methods on the Cornell box at grazing views and with cones leaving the
// grid (long cones, a wide aperture): every output finite, AO within [0, 1],
// and the outputs add up (image = direct + indirect).
TEST(Vct, OutputsAreFiniteAndAddUp) {
  RenderOutput v = test::render("builtin:cornell", "vct",
                                {"max_distance=100", "aperture=120", "shadows=true", "voxels=64x64x128"}, 48,
                                2, {"direct", "indirect", "ao", "specular"});
  const Image& img = v.result.image;
  const Image& d = v.result.aovs.at("direct");
  const Image& in = v.result.aovs.at("indirect");
  const Image& ao = v.result.aovs.at("ao");
  for (size_t i = 0; i < img.pixels.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      ASSERT_TRUE(std::isfinite(img.pixels[i][k])) << i;
      ASSERT_TRUE(std::isfinite(v.result.aovs.at("specular").pixels[i][k])) << i;
      EXPECT_NEAR(img.pixels[i][k], d.pixels[i][k] + in.pixels[i][k], 1e-4f + 1e-4f * img.pixels[i][k]) << i;
      EXPECT_GE(ao.pixels[i][k], 0.0f);
      EXPECT_LE(ao.pixels[i][k], 1.0f + 1e-5f);
    }
  EXPECT_GT(test::meanOf(in, 0), 0.0);
  RenderOutput a =
      test::render("builtin:cornell", "vct_ao", {"cones=3", "radius=100", "voxels=64x64x128"}, 48, 1);
  for (auto& p : a.result.image.pixels) ASSERT_TRUE(std::isfinite(p.x) && p.x >= 0.0f && p.x <= 1.0f + 1e-5f);
}

TEST(Vct, BadParametersAreRefused) {
  auto refused = [](const std::string& method, std::vector<std::string> set,
                    std::initializer_list<std::string> needles) {
    test::expectError([&] { test::render("builtin:cornell", method, set, 16, 1); }, needles);
  };
  refused("vct", {"radiance=atlas", "voxelizer=conservative"},
          {"voxelizer", "conservative", "radiance=atlas"});
  refused("vct", {"diffuse_cones=0"}, {"diffuse_cones", "0"});
  refused("vct", {"aperture=nan"}, {"aperture"});
  refused("vct", {"voxels=1024"}, {"voxels", "GiB"});
  refused("vct_ao", {"cones=4"}, {"cones", "4"});
  refused("vct_ao", {"aperture=150", "overlap=1.5"}, {"aperture", "overlap"});
  refused("vct_ao", {"radiance=atlas"}, {"radiance"});
  refused("vct", {"face_weights=cubed"}, {"face_weights", "cubed"});
  refused("vct", {"step=0"}, {"step", "0"});
  refused("vct", {"directional=level0", "volume=svo"}, {"directional", "volume=dense", "svo"});
  refused("vct", {"directional=level1", "radiance=texels"}, {"directional", "radiance=inject", "texels"});
  refused("vct", {"directional=level0", "anisotropic=false"}, {"directional", "anisotropic=true"});
  refused("vct", {"directional=true"}, {"directional", "true"});
  refused("vct", {"inject_small=-1"}, {"inject_small", "-1"});
  refused("vct", {"inject_small=100000"}, {"inject_small", "100000"});
  refused("vct", {"inject_small=8", "radiance=texels"}, {"inject_small", "radiance=inject", "texels"});
  refused("vct_ao", {"inject_small=8"}, {"inject_small"});
}

// A sealed hollow box whose walls are half a voxel thick, lit from outside
// (scenes/leak-closed/): the exact image is 0 inside. The walls' voxels hold
// the outer faces' light, and without `directional` they glow into the box
// from their unlit side (docs/BENCHMARKS.md, "Leaks: vct"); with
// directional=level1 the level-0 samples and the anisotropic chain's first
// level see a voxel from the cone's side: the leak falls by 40 % or more (here
// 0.097 → 0.057 at 128×64) and the lit room keeps 85 % of its light or more.
TEST(Vct, DirectionalRadianceKeepsTheWallsFromGlowingIntoTheBox) {
  const std::string scene = std::string(VGI_TEST_DATA) + "/../../scenes/leak-closed/closed-0.5v.json";
  const RenderOutput exact =
      test::render(scene, "reference", {"integrator=path", "maxdepth=2"}, 128, 64, {"indirect"});
  const RenderOutput plain = test::render(scene, "vct", {"directional=none"}, 128, 4, {"indirect"});
  const RenderOutput directional = test::render(scene, "vct", {"directional=level1"}, 128, 4, {"indirect"});
  const ImageDiff before = compareImages(plain.result.aovs.at("indirect"), exact.result.aovs.at("indirect"));
  const ImageDiff after =
      compareImages(directional.result.aovs.at("indirect"), exact.result.aovs.at("indirect"));
  EXPECT_GT(before.darkFraction, 0.2) << "the box's inside is dark in the exact image";
  EXPECT_GT(before.leak, 0.04) << "without it the walls glow inwards";
  EXPECT_LT(after.leak, 0.7 * before.leak) << "with it they glow outwards only";
  EXPECT_LT(after.relMse, before.relMse);
  for (int c = 0; c < 3; ++c) EXPECT_GT(after.energyRgb[c], 0.85 * before.energyRgb[c]) << c;
  EXPECT_EQ(directional.stats["extra"]["volume"]["directional"], "level1");
}

// Two rooms with a wall half a voxel thick between them (scenes/leak-walls/): the exact image is 0 in
// the right room. vct at its defaults leaks 3-4 % of the lit room's light there; the leak study's
// settings — directional=level1, the gather kit's wall remedies (its edge mask traced through the
// volume's grid, the fix-up's cones at full rate) and the level cap — cut it to about a quarter
// (docs/BENCHMARKS.md, "Leaks: vct": 0.7 % at 128×64).
TEST(Vct, LeakStudySettingsKeepTheLightInItsRoom) {
  const std::string scene = std::string(VGI_TEST_DATA) + "/../../scenes/leak-walls/wall-0.5v.json";
  const RenderOutput exact =
      test::render(scene, "reference", {"integrator=path", "maxdepth=2"}, 128, 256, {"indirect"});
  const RenderOutput plain = test::render(scene, "vct", {}, 128, 4, {"indirect"});
  const RenderOutput study =
      test::render(scene, "vct", {"directional=level1", "blur_visibility=true", "fixup=true", "max_level=3"},
                   128, 4, {"indirect"});
  const ImageDiff before = compareImages(plain.result.aovs.at("indirect"), exact.result.aovs.at("indirect"));
  const ImageDiff after = compareImages(study.result.aovs.at("indirect"), exact.result.aovs.at("indirect"));
  EXPECT_GT(before.darkFraction, 0.3) << "the right room is dark in the exact image";
  EXPECT_GT(before.leak, 0.025);
  EXPECT_LT(after.leak, 0.3 * before.leak) << before.leak;
  EXPECT_LT(after.relMse, before.relMse);
  EXPECT_GT(study.stats["timings_ms"].value("fixup", 0.0), 0.0) << "the fix-up ran";
  EXPECT_GT(study.stats["timings_ms"].value("gather_edges", 0.0), 0.0) << "the edge mask ran";
}

// A frame of an animation fills the cone volume again without the pass for its fixed-point range: the
// sums' pass takes the maximum with the last fill's range, and injects again only where it differs
// (ConeVolume, InjectionSums::inject); where only a dynamic mesh moved, only the cells it and its
// shadow covered before and after are injected (the range: the largest of the cells' own maxima),
// resolved and filtered up the chain again. Either way every frame equals a still at its time bit for
// bit (where the scene's bounds are the same at every frame: an animation's grid box is the union of
// its frames'): a light approaching the box (relit; its range grows: injected again; all cells), the
// bunny turning on the floor (the range stays: one pass over its cells) and the bunny rising to just
// under the light and sinking back (its top holds the largest pair: the range grows and shrinks with
// it, and the frames where it changes are injected again, all cells).
TEST(Vct, AnimationFramesEqualStillsWithoutTheRangePass) {
  const std::string lightScene = testing::TempDir() + "/vct_moving_light.json";
  std::ofstream(lightScene) << R"({"meshes": [{"path": "builtin:cornell"}], "lights": [{"type": "point",
      "position": [0.3, 0.4, 0.3], "intensity": 0.05, "keyframes": [
        {"time": 0, "position": [0.0, 0.0, 0.0]}, {"time": 1, "position": [0.3, 0.3, 0.3]}]}]})";
  const std::string bunny = std::string(VGI_TEST_DATA) + "/../../scenes/cornell-bunny.json";
  const std::string ply = test::sharedScene("stanford-bunny/bun_zipper.ply");  // "": the bunny's cases skip
  const std::string rising = testing::TempDir() + "/vct_rising_bunny.json";
  std::ofstream(rising) << R"({"meshes": [{"path": "builtin:cornell"}, {"path": ")" << ply
                        << R"(", "dynamic": true,
      "transform": {"translate": [0.0169, -0.0330, 0.0015]}, "keyframes": [
        {"time": 0, "translate": [0.28, 0.01, 0.28]}, {"time": 1, "translate": [0.28, 0.38, 0.28]},
        {"time": 2, "translate": [0.28, 0.01, 0.28]}]}]})";
  enum Kind { Light, Turning, Rising };
  for (Kind kind : {Light, Turning, Rising}) {
    if (kind != Light && ply.empty()) continue;
    const std::string scene = kind == Light ? lightScene : kind == Turning ? bunny : rising;
    const RenderOptions o = test::options(scene, "vct", {"temporal=false"}, 32, 1);
    const float step = kind == Turning ? 0.25f : 0.5f;
    const int n = kind == Rising ? 4 : 3;
    const test::Frames a = test::renderFrames(o, n, step);
    const std::vector<Image>& frames = a.images;
    ASSERT_EQ(frames.size(), size_t(n)) << scene;
    const nlohmann::json& stats = a.last.stats["frames"];
    int again = 0;
    for (int f = 0; f < n; ++f) {
      RenderOptions still = o;
      still.time = step * float(f);
      EXPECT_EQ(runRender(still).result.image.pixels, frames[size_t(f)].pixels) << scene << " frame " << f;
      const nlohmann::json& t = stats[size_t(f)]["timings_ms"];
      EXPECT_EQ(t.contains("vct_inject_max"), f == 0) << scene << " frame " << f << ": " << t.dump();
      again += t.contains("vct_inject_again") ? 1 : 0;
      if (f > 0 && kind != Rising) {
        EXPECT_EQ(t.contains("vct_inject_again"), kind == Light)
            << scene << " frame " << f << ": " << t.dump();
      }
      // The bunny's frames inject, resolve and filter only the cells it and its shadow left and
      // entered (unless its range changed); the moved light's, all of them.
      const nlohmann::json& volume = stats[size_t(f)]["extra"]["volume"];
      const uint64_t resolved = volume["resolved_cells"].get<uint64_t>(),
                     injected = volume["injected_cells"].get<uint64_t>();
      if (f == 0 || kind == Light || t.contains("vct_inject_again")) {
        EXPECT_EQ(resolved, 128u * 128u * 128u) << scene << " frame " << f;
        EXPECT_EQ(injected, 128u * 128u * 128u) << scene << " frame " << f;
      } else {
        EXPECT_LT(resolved, 128u * 128u * 128u / 8u) << scene << " frame " << f;
        EXPECT_EQ(injected, resolved) << scene << " frame " << f;
      }
    }
    if (kind == Rising) EXPECT_GE(again, 2) << "the range grew and shrank";
    EXPECT_GT(compareImages(frames[0], frames[2]).relMae, 0.001) << scene << ": it moved";
  }
}

// A moving frame's range is the largest of the injection's per-cell maxima (reduceCellMax): on the GPU
// exactly the CPU's largest word, wherever it lies — the first cell, the last, one in the middle — and
// for counts that fill no whole group, one cell, and more cells than invocations (each takes several).
TEST(ConeVolume, TheCellMaximaReduceToTheLargestWordWhereverItLies) {
  auto ctx = GlContext::create();
  ShaderLibrary shaders;
  std::mt19937 rng(7);
  for (uint64_t n :
       {uint64_t(1), uint64_t(63), uint64_t(1000), uint64_t(64 * 16 * 3 + 5), uint64_t(1) << 21}) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<uint32_t> words(n);
    for (auto& w : words) {
      const float v = u(rng) < 0.3f ? 0.0f : u(rng) * 4.0f;  // unlit cells: 0
      std::memcpy(&w, &v, 4);
    }
    for (uint64_t at : {uint64_t(0), n - 1, n / 2}) {
      std::vector<uint32_t> w = words;
      const float big = 5.0f + float(at % 7);
      std::memcpy(&w[at], &big, 4);
      unsigned bufs[2];
      glCreateBuffers(2, bufs);
      glNamedBufferStorage(bufs[0], GLsizeiptr(n * 4), w.data(), 0);
      const uint32_t zero = 0;
      glNamedBufferStorage(bufs[1], 4, &zero, 0);
      reduceCellMax(shaders, bufs[0], n, bufs[1]);
      uint32_t got = 0;
      glGetNamedBufferSubData(bufs[1], 0, 4, &got);
      glDeleteBuffers(2, bufs);
      EXPECT_EQ(got, *std::max_element(w.begin(), w.end())) << n << " cells, the largest at " << at;
    }
  }
  EXPECT_EQ(ctx->errorCount(), 0);
}

// inject_small: triangles whose bounding box spans at most that many cells are lit in the geometry
// shader (triangle-parallel: every cell of the box the triangle–box test confirms) instead of through
// the conservative rasterization (the same pairs, one per fragment column). A finely tessellated
// sphere in the Cornell box (12 k triangles, a fraction of a cell each at 128³): its light is the
// same either way — to the float rounding of a few contact pairs — in the volume and in the
// image; the big walls take the rasterization in both.
TEST(Vct, TriangleParallelInjectionLightsTheRasterizationsPairs) {
  const std::string obj = testing::TempDir() + "/vct_fine_sphere.obj";
  {
    std::ofstream f(obj);
    const int rings = 64, segments = 96;
    for (int i = 0; i <= rings; ++i)
      for (int j = 0; j < segments; ++j) {
        const float th = float(M_PI) * float(i) / float(rings),
                    ph = 2.0f * float(M_PI) * float(j) / float(segments);
        f << "v " << 0.28f + 0.1f * std::sin(th) * std::cos(ph) << " " << 0.1f + 0.1f * std::cos(th) << " "
          << -0.25f + 0.1f * std::sin(th) * std::sin(ph) << "\n";
      }
    for (int i = 0; i < rings; ++i)
      for (int j = 0; j < segments; ++j) {
        const int a = i * segments + j + 1, b = i * segments + (j + 1) % segments + 1;
        f << "f " << a << " " << b << " " << b + segments << "\nf " << a << " " << b + segments << " "
          << a + segments << "\n";
      }
  }
  const std::string scene = testing::TempDir() + "/vct_fine_sphere.json";
  std::ofstream(scene) << R"({"meshes": [{"path": "builtin:cornell"}, {"path": ")" << obj << R"("}]})";
  const RenderOutput raster = test::render(scene, "vct", {"inject_small=0"}, 64, 2, {"indirect"});
  const RenderOutput parallel = test::render(scene, "vct", {"inject_small=512"}, 64, 2, {"indirect"});
  const RenderOutput exact =
      test::render(scene, "reference", {"integrator=path", "maxdepth=2"}, 64, 64, {"indirect"});
  const Image& a = parallel.result.aovs.at("indirect");
  const Image& b = raster.result.aovs.at("indirect");
  const ImageDiff d = compareImages(a, b);
  EXPECT_LT(d.relMae, 1e-4) << "the same pairs, the same light";
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(d.energyRgb[c], 1.0f, 1e-4f) << c;
  // Not trivially so: the sphere's own light is a visible part of the image (a vct without its
  // small triangles' light would differ by far more than the paths do).
  const ImageDiff toExact = compareImages(b, exact.result.aovs.at("indirect"));
  EXPECT_LT(toExact.relMae, 0.5);
  EXPECT_EQ(parallel.stats["params"]["inject_small"], 512);
}

// The constellations' weights are the cosine-weighted hemisphere's shares:
// they sum to 1, and a symmetric ring's axes share equally.
TEST(ConeVolume, ConstellationWeightsPartitionTheHemisphere) {
  for (auto c : {ringConstellation(true, 5, 63.4349f), ringConstellation(false, 3, 45.0f),
                 ringConstellation(true, 4, 55.0f), ringConstellation(true, 7, 60.0f)}) {
    double sum = 0;
    for (auto& w : c) sum += w.w;
    EXPECT_NEAR(sum, 1.0, 1e-6);
    for (size_t k = 2; k < c.size(); ++k) EXPECT_NEAR(c[k].w, c[1].w, 2e-3);
  }
}

}  // namespace vgi
