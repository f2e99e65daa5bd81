// The sparse voxel octree (voxelize/sparse_octree.h, illum/resources/sparse_octree.h,
// CONE_SVO in shaders/illum/vct/cones.glsl): the GPU build equals the C++
// reference structure at several depths and non-power-of-two grids (with and
// without dilation); the leaves and every filtered level equal the dense
// volume built from the same sums, texel for texel; a single lit leaf filters
// to the closed form and a uniform region to itself; cones through the octree
// equal cones through the dense volume (with dilation everywhere; without it,
// except where a brick border intervenes, which is counted); degenerate cones
// stay finite; the renders of vct and vct_ao with volume=svo, and bad parameters.
#include "shaders/shared/sparse_octree.glsl"

#include <glad/gl.h>

#include <cmath>
#include <random>
#include <set>

#include "cone_fixture.h"
#include "core/image_metrics.h"
#include "illum/kits/cone_kit.h"
#include "render_util.h"
#include "test_util.h"
#include "voxelize/sparse_octree.h"

namespace vgi {

namespace {

using test::halfStep;
using test::toHalf;
using test::unitBox;
using test::VolumeFixture;

size_t cellIndex(const GridBox& box, glm::uvec3 c) {
  return (size_t(c.z) * box.resolution.y + c.y) * box.resolution.x + c.x;
}

// Random cells: clusters (surfaces) and scattered ones.
std::vector<glm::uvec3> randomCells(const GridBox& box, uint32_t seed, int count) {
  std::mt19937 rng(seed);
  const glm::uvec3 r = box.resolution;
  std::vector<glm::uvec3> out;
  for (int i = 0; i < count; ++i) {
    glm::uvec3 c(rng() % r.x, rng() % r.y, rng() % r.z);
    out.push_back(c);
    if (i % 2 == 0)  // a small plate around it
      for (uint32_t a = 0; a < 4; ++a)
        for (uint32_t b = 0; b < 4; ++b) {
          const glm::uvec3 p(std::min(c.x + a, r.x - 1), std::min(c.y + b, r.y - 1), c.z);
          out.push_back(p);
        }
  }
  return out;
}

// The dense volume and the octree over the same grid and sums.
struct Both {
  VolumeFixture dense;
  std::unique_ptr<SparseVoxelOctree> octree;
  Both(const GridBox& box, bool anisotropic, bool dilate, const BinaryGrid& grid,
       const std::vector<uint32_t>& counts, const std::vector<uint32_t>& sums, float radianceMax)
      : dense(box, anisotropic ? ValueMips::Anisotropic : ValueMips::Isotropic, grid, counts, sums,
              radianceMax) {
    GlPyramid pyramid(box);
    pyramid.build(grid, dense.shaders);
    octree = std::make_unique<SparseVoxelOctree>(box, anisotropic, dilate);
    octree->build(pyramid.words(), dense.shaders, dense.prof);
    // The leaves' sums in slot order, from the cells' (what the injection writes).
    const std::vector<uint32_t> leaves = octree->readLeafCells();
    std::vector<uint32_t> lc(std::max<size_t>(leaves.size(), 1), 0), ls(lc.size() * 4, 0);
    for (size_t i = 0; i < leaves.size(); ++i) {
      const glm::uvec3 c = shared::svoUnpackCell(leaves[i]);
      if (c.x >= box.resolution.x || c.y >= box.resolution.y || c.z >= box.resolution.z) continue;
      const size_t k = cellIndex(box, c);
      lc[i] = counts[k];
      for (int j = 0; j < 4; ++j) ls[i * 4 + j] = sums[k * 4 + j];
    }
    GlBuffer cb = makeBuffer(lc.size() * 4), sb = makeBuffer(ls.size() * 4);
    glNamedBufferSubData(cb.get(), 0, GLsizeiptr(lc.size() * 4), lc.data());
    glNamedBufferSubData(sb.get(), 0, GLsizeiptr(ls.size() * 4), ls.data());
    octree->resolve(cb.get(), sb.get(), radianceMax, dense.shaders, dense.prof);
    glFinish();
  }
};

// Random counts and sums for every cell (set cells without light, lit cells without the bit).
void randomSums(const GridBox& box, uint32_t seed, float radianceMax, std::vector<uint32_t>& counts,
                std::vector<uint32_t>& sums) {
  std::mt19937 rng(seed);
  counts.assign(box.cellCount(), 0);
  sums.assign(box.cellCount() * 4, 0);
  for (size_t i = 0; i < counts.size(); ++i) {
    counts[i] = rng() % 4;
    for (uint32_t k = 0; k < 3 && counts[i]; ++k)
      sums[i * 4 + k] = counts[i] * shared::toFixedRadiance(float(rng() % 1000) / 500.0f, radianceMax);
  }
}

void expectSameTexel(glm::vec4 got, glm::vec4 want, const std::string& what, int& bad) {
  for (int k = 0; k < 4; ++k)
    if (got[k] != want[k] && bad++ < 5)
      ADD_FAILURE() << what << " c" << k << ": " << got[k] << " vs " << want[k];
}

}  // namespace

// The GPU build (fragments from the grid's words, flag / allocate per level)
// equals svoReferenceStructure (the same rule in C++) node for node: the
// cells of the nodes with children at every level, the occupied leaves, the
// node counts — at depths 7, 8 and 9, on non-power-of-two and non-cubic grids.
TEST(SparseOctree, TheGpuBuildEqualsTheCppReference) {
  auto gl = GlContext::create();
  ShaderLibrary shaders;
  Profiler prof(true);
  const glm::uvec3 grids[] = {{128, 128, 128}, {48, 80, 128}, {200, 40, 256}, {16, 300, 512}};
  for (glm::uvec3 res : grids)
    for (bool dilate : {false, true}) {
      const GridBox box = unitBox(res);
      BinaryGrid grid(box);
      const std::vector<glm::uvec3> cells = randomCells(box, res.x + res.y, 300);
      for (const glm::uvec3& c : cells) grid.set(c.x, c.y, c.z);
      std::set<uint32_t> unique;
      std::vector<glm::uvec3> fragments;
      for (const glm::uvec3& c : cells)
        if (unique.insert(shared::svoPackCell(c)).second) fragments.push_back(c);
      GlPyramid pyramid(box);
      pyramid.build(grid, shaders);
      SparseVoxelOctree octree(box, true, dilate);
      octree.build(pyramid.words(), shaders, prof);
      const std::string what = std::to_string(res.x) + "x" + std::to_string(res.y) + "x" +
                               std::to_string(res.z) + (dilate ? " dilated" : "");
      EXPECT_EQ(octree.fragmentCount(), grid.count()) << what;
      EXPECT_EQ(octree.depth(), svoDepth(res)) << what;
      const SvoStructure want = svoReferenceStructure(fragments, octree.depth(), dilate);
      const SvoStructure got = octree.readStructure();
      ASSERT_EQ(got.flagged.size(), want.flagged.size()) << what;
      for (size_t l = 0; l < want.flagged.size(); ++l) {
        EXPECT_EQ(got.nodes[l], want.nodes[l]) << what << " level " << l;
        EXPECT_TRUE(got.flagged[l] == want.flagged[l])
            << what << " level " << l << ": " << got.flagged[l].size() << " flagged vs "
            << want.flagged[l].size();
        EXPECT_TRUE(got.occupied[l] == want.occupied[l])
            << what << " level " << l << ": " << got.occupied[l].size() << " occupied vs "
            << want.occupied[l].size();
      }
      EXPECT_EQ(gl->errorCount(), 0);
    }
}

// The leaves equal the dense volume's level 0 cell for cell (every cell of the
// grid: those outside the tree are 0 in the dense volume), and every level
// above — each anisotropic face, or the isotropic means — equals the dense
// chain's texel of the same cell, bit for bit (the same kernels on the same
// half floats), on a cubic power-of-two grid where the dense chain's texels
// are the octree's nodes; on a non-cubic one the leaves.
TEST(SparseOctree, LeavesAndLevelsEqualTheDenseVolume) {
  const float radianceMax = 2.0f;
  for (glm::uvec3 res : {glm::uvec3(128, 128, 128), glm::uvec3(48, 80, 128)})
    for (bool anisotropic : {true, false}) {
      const GridBox box = unitBox(res);
      BinaryGrid grid(box);
      for (const glm::uvec3& c : randomCells(box, 7, 400)) grid.set(c.x, c.y, c.z);
      std::vector<uint32_t> counts, sums;
      randomSums(box, 11, radianceMax, counts, sums);
      Both b(box, anisotropic, false, grid, counts, sums, radianceMax);
      const std::string what =
          std::to_string(res.x) + "x" + std::to_string(res.y) + (anisotropic ? " aniso" : " iso");
      const uint32_t depth = b.octree->depth();
      const std::map<uint32_t, glm::vec4> leaves = b.octree->readLevel(depth, -1);
      const std::vector<glm::vec4> level0 = b.dense.tex->read("radiance", 0);
      int bad = 0, occupied = 0;
      for (uint32_t z = 0; z < res.z; ++z)
        for (uint32_t y = 0; y < res.y; ++y)
          for (uint32_t x = 0; x < res.x; ++x) {
            const glm::uvec3 c(x, y, z);
            const auto it = leaves.find(shared::svoPackCell(c));
            const glm::vec4 want = level0[cellIndex(box, c)];
            occupied += want.w > 0.0f;
            expectSameTexel(it == leaves.end() ? glm::vec4(0.0f) : it->second, want, what + " leaf", bad);
          }
      EXPECT_EQ(bad, 0) << what;
      EXPECT_EQ(uint64_t(occupied), grid.count()) << what;
      if (res.x != res.y || res.x != res.z) continue;
      for (uint32_t l = 1; l <= depth; ++l)
        for (int f = anisotropic ? 0 : -1; f < (anisotropic ? 6 : 0); ++f) {
          const std::vector<glm::vec4> dense = anisotropic ? b.dense.tex->readAniso("radiance", f, int(l))
                                                           : b.dense.tex->read("radiance", int(l));
          const glm::uvec3 s = b.dense.tex->levelSize(int(l));
          const std::map<uint32_t, glm::vec4> level = b.octree->readLevel(depth - l, f);
          int badLevel = 0;
          for (const auto& [cell, v] : level) {
            const glm::uvec3 c = shared::svoUnpackCell(cell);
            expectSameTexel(v, dense[(size_t(c.z) * s.y + c.y) * s.x + c.x],
                            what + " level " + std::to_string(l) + " face " + std::to_string(f), badLevel);
          }
          // A texel without a node is empty.
          size_t nonzero = 0;
          for (const glm::vec4& v : dense) nonzero += v.w > 0.0f;
          size_t nodesNonzero = 0;
          for (const auto& [cell, v] : level) nodesNonzero += v.w > 0.0f;
          EXPECT_EQ(nonzero, nodesNonzero) << what << " level " << l;
          EXPECT_EQ(badLevel, 0) << what << " level " << l << " face " << f;
        }
      EXPECT_EQ(b.dense.gl->errorCount(), 0);
    }
}

// One lit leaf (L, 1) alone: every anisotropic face sees it as (L, 1)·4^-k at
// k levels above the leaves (one of the four lines of each block, composed
// with empty cells), the isotropic chain as (L, 1)·8^-k; a uniform 16³ block
// filters to itself at every level inside it.
TEST(SparseOctree, ASingleLitLeafAndAUniformRegionFilterToTheClosedForms) {
  const GridBox box = unitBox({128, 128, 128});
  const float radianceMax = 1.0f;
  const glm::vec3 L(0.8f, 0.4f, 0.2f);
  for (bool anisotropic : {true, false}) {
    BinaryGrid grid(box);
    const glm::uvec3 c(21, 42, 77);
    grid.set(c.x, c.y, c.z);
    std::vector<uint32_t> counts(box.cellCount(), 0), sums(box.cellCount() * 4, 0);
    auto light = [&](glm::uvec3 p) {
      const size_t i = cellIndex(box, p);
      counts[i] = 1;
      for (int k = 0; k < 3; ++k) sums[i * 4 + k] = shared::toFixedRadiance(L[k], radianceMax);
    };
    light(c);
    const glm::uvec3 block(64, 32, 96);  // a 16³ block, aligned to level 3's 16-cell nodes
    for (uint32_t z = 0; z < 16; ++z)
      for (uint32_t y = 0; y < 16; ++y)
        for (uint32_t x = 0; x < 16; ++x) {
          grid.set(block.x + x, block.y + y, block.z + z);
          light(block + glm::uvec3(x, y, z));
        }
    Both b(box, anisotropic, false, grid, counts, sums, radianceMax);
    const uint32_t depth = b.octree->depth();
    const glm::vec3 Lh(toHalf(L.x), toHalf(L.y), toHalf(L.z));
    for (uint32_t k = 1; k <= 4; ++k)
      for (int f = anisotropic ? 0 : -1; f < (anisotropic ? 6 : 0); ++f) {
        const std::map<uint32_t, glm::vec4> level = b.octree->readLevel(depth - k, f);
        const std::string what =
            std::string(anisotropic ? "face " + std::to_string(f) : "iso") + " level " + std::to_string(k);
        const float a = std::pow(anisotropic ? 0.25f : 0.125f, float(k));
        const glm::vec4 got = level.at(shared::svoPackCell(c >> glm::uvec3(k)));
        EXPECT_NEAR(got.w, a, halfStep(a)) << what;
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(got[j], Lh[j] * a, 4 * halfStep(Lh[j] * a)) << what;
        // Inside the block (levels up to 4: one node of 16³).
        const glm::vec4 inside = level.at(shared::svoPackCell(block >> glm::uvec3(k)));
        EXPECT_NEAR(inside.w, 1.0f, halfStep(1.0f)) << what << " (uniform)";
        for (int j = 0; j < 3; ++j)
          EXPECT_NEAR(inside[j], Lh[j], 2 * halfStep(Lh[j])) << what << " (uniform)";
      }
  }
}

// Cones through the octree equal cones through the dense volume built from
// the same sums, with and without empty-space skipping: with dilation (every
// stencil's brick allocated) all of them, to the rounding of the texture
// units' filtering; without it, the cones that differ are those where an empty
// node's stencil misses a filled neighbour (VCT-AO §6.2), counted here and
// bounded. Degenerate cones stay finite.
TEST(SparseOctree, ConesEqualConesThroughTheDenseVolume) {
  const GridBox box = unitBox({128, 128, 128});
  const float radianceMax = 2.0f;
  BinaryGrid grid(box);
  for (const glm::uvec3& c : randomCells(box, 3, 3000)) grid.set(c.x, c.y, c.z);
  std::vector<uint32_t> counts, sums;
  randomSums(box, 5, radianceMax, counts, sums);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<ProbeCone> cones;
  for (int i = 0; i < 400; ++i) {
    const glm::vec3 d = glm::normalize(glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f));
    cones.push_back({glm::vec3(u(rng), u(rng), u(rng)), d, std::tan(glm::radians(1.0f + 40.0f * u(rng))),
                     0.2f + 0.8f * u(rng)});
  }
  const size_t random = cones.size();
  for (float tanHalf : {0.0f, 1e3f})
    for (float length : {0.0f, 1e-9f, 5.0f})
      for (glm::vec3 apex : {glm::vec3(0.5f), glm::vec3(-1.0f), glm::vec3(0.0f), glm::vec3(0.9999f)})
        cones.push_back({apex, glm::normalize(glm::vec3(1.0f, 1e-7f, 0.0f)), tanHalf, length});
  for (bool anisotropic : {true, false})
    for (bool dilate : {true, false}) {
      Both b(box, anisotropic, dilate, grid, counts, sums, radianceMax);
      const std::string what = std::string(anisotropic ? "aniso" : "iso") + (dilate ? " dilated" : "");
      for (bool skip : {false, true}) {
        const std::vector<ProbeResult> d = traceConesGl(*b.dense.tex, b.dense.shaders, cones, 1.0f, skip);
        const std::vector<ProbeResult> s = traceConesGl(*b.octree, b.dense.shaders, cones, 1.0f, skip);
        int differ = 0;
        double worst = 0;
        for (size_t k = 0; k < random; ++k) {
          double e = 0;
          for (int c = 0; c < 4; ++c)
            e = std::max(e, double(std::abs(s[k].radianceOpacity[c] - d[k].radianceOpacity[c])) /
                                (0.02 + std::abs(d[k].radianceOpacity[c])));
          worst = std::max(worst, e);
          differ += e > 0.01;
        }
        for (size_t k = random; k < cones.size(); ++k)
          for (int c = 0; c < 4; ++c) {
            ASSERT_TRUE(std::isfinite(s[k].radianceOpacity[c])) << what << " degenerate cone " << k;
            ASSERT_TRUE(std::isfinite(s[k].occlusionEscapedSamples[c])) << what << " degenerate cone " << k;
          }
        RecordProperty(what + (skip ? " skip" : "") + " differing", differ);
        std::printf("%s%s: %d of %zu cones differ by > 1%% (worst %.4f)\n", what.c_str(), skip ? " skip" : "",
                    differ, random, worst);
        if (dilate) {
          EXPECT_EQ(differ, 0) << what << " worst " << worst;  // empty-space skipping included
        } else {
          EXPECT_LT(differ, int(random) / 2) << what;  // the brick-border artefact: some, not most
        }
      }
      EXPECT_EQ(b.dense.gl->errorCount(), 0);
    }
}

// vct and vct_ao with volume=svo render finite outputs and agree with the
// dense volume on the Cornell box (the same leaves: within a few per cent).
TEST(SparseOctree, VctAndVctAoRenderLikeTheDenseVolume) {
  for (const std::string method : {"vct", "vct_ao"}) {
    auto run = [&](std::vector<std::string> set) {  // vct: the indirect light; vct_ao: the AO (its image)
      if (method == "vct_ao") return test::render("builtin:cornell", method, set, 64, 1).result.image;
      return test::render("builtin:cornell", method, set, 64, 1, {"indirect"}).result.aovs.at("indirect");
    };
    const Image dense = run({"voxels=128"});
    const Image svo = run({"voxels=128", "volume=svo"});
    const ImageDiff m = compareImages(svo, dense);  // throws on a non-finite value
    EXPECT_LT(m.relMae, 0.03) << method;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(m.energyRgb[k], 1.0, 0.02) << method;
  }
}

// Injection reaches every occupied leaf when it rasterizes the triangles
// (radiance=inject: the conservative voxelizer's cells are the rasterization's
// own), while the article's light-map texels leave holes, more of them the
// coarser the maps (radiance=texels; the light's view of the Cornell box).
TEST(SparseOctree, TexelInjectionLeavesHolesWhereTheMapsAreCoarse) {
  auto holes = [](std::vector<std::string> set) {
    set.push_back("volume=svo");
    set.push_back("voxels=128");
    const RenderOutput r = test::render("builtin:cornell", "vct", set, 32, 1);
    return r.stats["extra"]["volume"]["unreached_leaves"].get<double>();
  };
  EXPECT_EQ(holes({"radiance=inject"}), 0.0);
  const double fine = holes({"radiance=texels", "shadow_res=2048"});
  const double coarse = holes({"radiance=texels", "shadow_res=64"});
  EXPECT_GT(coarse, 2.0 * fine + 100.0) << fine;
}

// update_every=k on the rotating bunny: the tree is rebuilt at frames 0, k,
// 2k… (svo_build runs only then) and lags 1 … k−1 frames in between; its
// leaves are lit every frame; the lagging frames' indirect light differs from
// the rebuilt tree's (the moved bunny's new cells are not in the old tree).
TEST(SparseOctree, UpdateEveryRebuildsTheTreeEveryKthFrame) {
  if (test::sharedScene("").empty()) GTEST_SKIP() << "the shared scenes (the Stanford bunny) are absent";
  RenderOptions o;
  o.scene = std::string(VGI_TEST_DATA) + "/../../scenes/cornell-bunny.json";
  o.method = "vct";
  o.width = o.height = 32;
  o.spp = 1;
  o.progress = false;
  o.frames = 5;
  o.timeStep = 0.1f;
  o.aovs = {"indirect"};
  std::vector<Image> images[2];
  for (int k : {1, 3}) {
    o.set = {"volume=svo", "update_every=" + std::to_string(k), "temporal=false"};  // frames compared as such
    std::vector<int> lags, builds;
    runRender(o, [&](int, const RenderOutput& r) {
      lags.push_back(r.stats["extra"]["volume"]["lag_frames"].get<int>());
      builds.push_back(r.stats["timings_ms"].contains("svo_build") ? 1 : 0);
      images[k == 3].push_back(r.result.aovs.at("indirect"));
    });
    const std::vector<int> wantLag =
        k == 1 ? std::vector<int>{0, 0, 0, 0, 0} : std::vector<int>{0, 1, 2, 0, 1};
    EXPECT_EQ(lags, wantLag) << "update_every " << k;
    const std::vector<int> wantBuild =
        k == 1 ? std::vector<int>{1, 1, 1, 1, 1} : std::vector<int>{1, 0, 0, 1, 0};
    EXPECT_EQ(builds, wantBuild) << "update_every " << k;
  }
  ASSERT_EQ(images[0].size(), 5u);
  ASSERT_EQ(images[1].size(), 5u);
  // Rebuilt: the same tree (its bricks may lie elsewhere in the pools: float rounding).
  EXPECT_LT(compareImages(images[1][3], images[0][3]).relMae, 1e-5);
  EXPECT_GT(compareImages(images[1][2], images[0][2]).relMae, 1e-3);  // two frames behind
}

TEST(SparseOctree, BadParametersAreRefused) {
  auto refused = [](const std::string& method, std::vector<std::string> set,
                    std::initializer_list<std::string> needles) {
    test::expectError([&] { test::render("builtin:cornell", method, set, 16, 1); }, needles);
  };
  refused("vct", {"volume=octree"}, {"volume", "octree"});
  refused("vct", {"volume=svo", "voxels=2048x128x128"}, {"voxels", "2048"});
  refused("vct", {"volume=svo", "radiance=atlas", "voxelizer=atlas"}, {"radiance", "atlas"});
  refused("vct", {"volume=svo", "update_every=0"}, {"update_every", "0"});
  refused("vct_ao", {"volume=svo", "dilate=maybe"}, {"dilate", "maybe"});
}

}  // namespace vgi
