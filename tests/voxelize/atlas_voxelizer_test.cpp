// The GL atlas voxelizer (llvmpipe in CI): its insertion equals the CPU build of
// the same kernel bit for bit, and its grid is measured against the exact one.
#include "voxelize/atlas_voxelizer.h"

#include <fstream>
#include <random>

#include "core/gl_context.h"
#include "core/scene_loader.h"
#include "core/shader_library.h"
#include "shaders/shared/sampling.glsl"
#include "test_util.h"
#include "traverse/gl_ray_tracer.h"
#include "traverse/or_mip_pyramid.h"
#include "voxelize/conservative_voxelizer.h"
#include "voxelize/exact_voxelizer.h"
#include "voxelize/grid_metrics.h"
#include "voxelize/slicemap_voxelizer.h"

namespace vgi {

namespace test {
struct GlFixture {
  std::unique_ptr<GlContext> gl = GlContext::create();
  ShaderLibrary shaders;
  VoxelizeRequest request(const Scene& s, glm::uvec3 res, float time = 0) {
    VoxelizeRequest r;
    r.scene = &s;
    r.box = fitGridBox(s, res, time);
    r.time = time;
    r.gl = gl.get();
    r.shaders = &shaders;
    return r;
  }
};
}  // namespace test
using test::GlFixture;

TEST(AtlasVoxelizer, GpuInsertionEqualsCpuBitForBit) {
  GlFixture f;
  Scene s = loadScene("builtin:cornell");
  VoxelizeRequest r = f.request(s, {64, 48, 256});
  r.atlasFootprint = 0.0f;  // the paper's single point per texel: integer kernel, bit for bit
  Profiler prof(true);
  nlohmann::json stats;
  std::vector<AtlasSamples> points;
  BinaryGrid gpu = voxelizeAtlasGl(r, prof, stats, &points);
  BinaryGrid cpu(r.box);
  long valid = 0;
  for (auto& atlas : points) {
    insertAtlasPoints(atlas, cpu);
    for (auto& p : atlas.positions) valid += p.w != 0.0f;
  }
  EXPECT_EQ(gpu.words(), cpu.words());
  EXPECT_EQ(stats["points"].get<long>(), valid);
  EXPECT_EQ(f.gl->errorCount(), 0);
}

// With footprints the cells also come from the float triangle–box test; its
// GLSL is `precise` (no fused multiply-adds), so GPU and CPU still agree bit for
// bit, and on the Cornell box the grid equals the exact one.
TEST(AtlasVoxelizer, GpuFootprintInsertionEqualsCpuBitForBit) {
  GlFixture f;
  Scene s = loadScene("builtin:cornell");
  VoxelizeRequest r = f.request(s, {64, 48, 256});
  Profiler prof(true);
  nlohmann::json stats;
  std::vector<AtlasSamples> points;
  BinaryGrid gpu = voxelizeAtlasGl(r, prof, stats, &points);
  BinaryGrid cpu(r.box);
  for (auto& atlas : points) {
    EXPECT_GT(atlas.footprint, 0.0f);
    insertAtlasPoints(atlas, cpu);
  }
  EXPECT_EQ(gpu.words(), cpu.words());
  GridComparison c = compareGrids(gpu, voxelizeExact(s, r.box));
  EXPECT_EQ(c.precision(), 1.0);
  EXPECT_GE(c.recall(), 0.999);
  EXPECT_EQ(f.gl->errorCount(), 0);
}

TEST(AtlasVoxelizer, CornellBoxAgainstTheExactVoxelizer) {
  GlFixture f;
  Scene s = loadScene("builtin:cornell");
  VoxelizeRequest r = f.request(s, {64, 64, 128});
  Profiler prof(true);
  nlohmann::json stats;
  BinaryGrid atlas = voxelizeAtlasGl(r, prof, stats);
  GridComparison c = compareGrids(atlas, voxelizeExact(s, r.box));
  // Points and their footprints stay inside the exact set; the footprints
  // catch the grazed cells (corner cuts) single points miss (docs/BENCHMARKS.md).
  EXPECT_GE(c.precision(), 0.9999);
  EXPECT_GE(c.recall(), 0.999);
  EXPECT_EQ(stats["triangles_without_texels"], 0);
}

TEST(AtlasVoxelizer, SliversStillProduceTexelsAndVoxels) {
  GlFixture f;
  Scene s;
  // Two long needles (width 1e-4 of their length) and a normal triangle.
  test::addMesh(s,
                {{0, 0, 0},
                 {1, 0.3f, 0.2f},
                 {1, 0.3001f, 0.2f},
                 {0, 1, 1},
                 {0.9f, 0.1f, 0.95f},
                 {0.9f, 0.1f, 0.9501f},
                 {0.2f, 0.8f, 0.1f},
                 {0.5f, 0.9f, 0.3f},
                 {0.3f, 0.6f, 0.5f}},
                {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}});
  VoxelizeRequest r = f.request(s, {64, 64, 128});
  Profiler prof(true);
  nlohmann::json stats;
  BinaryGrid atlas = voxelizeAtlasGl(r, prof, stats);
  EXPECT_EQ(stats["triangles_without_texels"], 0);
  BinaryGrid exact = voxelizeExact(s, r.box);
  GridComparison c = compareGrids(atlas, exact);
  // The footprint cells come from a float triangle–box test, which on a needle
  // 1e-4 wide may accept a cell the double-precision test rejects by a hair.
  EXPECT_GE(c.precision(), 0.99);
  {
    VoxelizeRequest pointOnly = r;  // the paper's single points lie on the surface: exact precision
    pointOnly.atlasFootprint = 0.0f;
    Profiler p2(true);
    nlohmann::json s2;
    GridComparison c0 = compareGrids(voxelizeAtlasGl(pointOnly, p2, s2), exact);
    EXPECT_GE(c0.precision(), 0.9999);
    EXPECT_GE(c.recall(), c0.recall());
  }
  // A needle is a segment: its edges are rasterized as lines in the atlas, so
  // consecutive points are at most √2 texels apart along it. Every cell the
  // needle crosses with a longer chord must hold a point. (Cells it only grazes
  // are in the exact set but may be missed: recall is measured, not assumed.)
  const float texel = stats["texel_world"].get<float>();
  const shared::GridParams g = r.box.params();
  int checked = 0;
  for (auto [a, b] : {std::pair{glm::vec3(0, 0, 0), glm::vec3(1, 0.30005f, 0.2f)},
                      std::pair{glm::vec3(0, 1, 1), glm::vec3(0.9f, 0.1f, 0.95005f)}}) {
    glm::vec3 qa = shared::worldToGrid(g, a), qb = shared::worldToGrid(g, b);
    const float len = glm::length(b - a);
    for (uint32_t z = 0; z < 128; ++z)
      for (uint32_t y = 0; y < 64; ++y)
        for (uint32_t x = 0; x < 64; ++x) {
          float t0 = 0, t1 = 1;  // clip the segment to the cell (slabs)
          for (int k = 0; k < 3; ++k) {
            float lo = float(k == 0 ? x : k == 1 ? y : z), d = qb[k] - qa[k];
            if (std::abs(d) < 1e-12f) {
              if (qa[k] < lo || qa[k] > lo + 1) t0 = 2;
              continue;
            }
            float u0 = (lo - qa[k]) / d, u1 = (lo + 1 - qa[k]) / d;
            t0 = std::max(t0, std::min(u0, u1));
            t1 = std::min(t1, std::max(u0, u1));
          }
          if (t1 - t0 > 0 && (t1 - t0) * len > 1.5f * std::sqrt(2.0f) * texel) {
            ++checked;
            EXPECT_TRUE(atlas.test(x, y, z)) << "needle crosses " << x << "," << y << "," << z
                                             << " with chord " << (t1 - t0) * len / texel << " texels";
          }
        }
  }
  EXPECT_GT(checked, 60);
}

TEST(AtlasVoxelizer, MovedDynamicObjectLeavesNoStaleVoxels) {
  GlFixture f;
  Scene s = loadScene(test::writeMovingTriangleScene("moving"));
  GridBox box = fitGridBox(s, {64, 64, 128}, 0.0f);
  for (float t : {0.0f, 1.0f}) {
    VoxelizeRequest r = f.request(s, {64, 64, 128}, t);
    r.box = box;
    Profiler prof(true);
    nlohmann::json stats;
    BinaryGrid atlas = voxelizeAtlasGl(r, prof, stats);
    GridComparison c = compareGrids(atlas, voxelizeExact(s, box, t));
    EXPECT_GE(c.precision(), 0.9999) << "stale voxels at time " << t;
    EXPECT_GE(c.recall(), 0.95) << t;
  }
}

}  // namespace vgi

namespace vgi {
// Slicemap: exact where triangles face the depth axis, holes where they are
// seen edge-on — the comparison the VGI paper draws (§3.3, Fig. 4).
TEST(SlicemapVoxelizer, FacingTrianglesAreFoundEdgeOnOnesAreNot) {
  GlFixture f;
  Scene s;
  Mesh& mesh = test::addMesh(s, {}, {});
  // A quad facing +z (normal along the depth axis) and one lying in a plane that contains z.
  mesh.positions = {{0.05f, 0.05f, 0.3f},
                    {0.95f, 0.05f, 0.3f},
                    {0.95f, 0.95f, 0.3f},
                    {0.05f, 0.95f, 0.3f},
                    {0.51f, 0.05f, 0.05f},
                    {0.51f, 0.95f, 0.05f},
                    {0.51f, 0.95f, 0.95f},
                    {0.51f, 0.05f, 0.95f},
                    {0, 0, 0},
                    {1, 1, 1},
                    {1, 1.0001f, 1}};  // a needle stretching the box to [0,1]³
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}, {8, 9, 10}};
  VoxelizeRequest r = f.request(s, {64, 64, 128});
  Profiler prof(true);
  nlohmann::json stats;
  BinaryGrid slice = voxelizeSlicemapGl(r, prof, stats);
  Scene facing = s, edgeOn = s;
  facing.meshes[0].triangles = {{0, 1, 2}, {0, 2, 3}};
  edgeOn.meshes[0].triangles = {{4, 5, 6}, {4, 6, 7}};
  GridComparison cf = compareGrids(slice, voxelizeExact(facing, r.box, 0, 0, kInteriorShrink));
  GridComparison ce = compareGrids(slice, voxelizeExact(edgeOn, r.box, 0, 0, kInteriorShrink));
  EXPECT_GE(cf.recall(), 0.999);  // one fragment per column: the facing quad is complete
  EXPECT_GT(ce.exact, 1000u);     // (the quad is inside a cell column, not on a boundary)
  EXPECT_LT(ce.recall(), 0.1);    // the edge-on quad is one pixel wide at most: mostly holes
  EXPECT_GE(compareGrids(slice, voxelizeExact(s, r.box)).precision(), 0.999);
  EXPECT_EQ(f.gl->errorCount(), 0);
}
}  // namespace vgi

namespace vgi {
// The conservative GPU voxelizer confirms each candidate cell with the float
// triangle–box test: it must agree with the exact CPU voxelizer up to float
// rounding on contacts — on hard inputs (huge, tiny, sliver, boundary-aligned
// triangles) and on a non-cubic grid. So must the hybrid at any cutoff, which
// counts every triangle in exactly one of its two paths.
TEST(ConservativeVoxelizer, MatchesTheExactVoxelizer) {
  GlFixture f;
  Scene cornell = loadScene("builtin:cornell");
  Scene hard;
  Mesh& mesh = test::addMesh(hard, {}, {});
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(0, 1);
  for (int i = 0; i < 200; ++i) {  // random triangles of every size
    glm::vec3 c(u(rng), u(rng), u(rng));
    float s = std::pow(10.0f, -3.0f + 3.0f * u(rng));
    uint32_t b = uint32_t(mesh.positions.size());
    for (int k = 0; k < 3; ++k) mesh.positions.push_back(c + s * (glm::vec3(u(rng), u(rng), u(rng)) - 0.5f));
    mesh.triangles.push_back({b, b + 1, b + 2});
  }
  uint32_t b = uint32_t(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), {{0, 0, 0}, {1, 1, 1}, {1, 1.0001f, 1}});  // a needle
  mesh.triangles.push_back({b, b + 1, b + 2});
  for (const Scene* s : {&cornell, &hard})
    for (glm::uvec3 res : {glm::uvec3(64, 64, 128), glm::uvec3(40, 72, 256)}) {
      VoxelizeRequest r = f.request(*s, res);
      Profiler prof(true);
      nlohmann::json stats;
      BinaryGrid g = voxelizeConservativeGl(r, prof, stats);
      const BinaryGrid exact = voxelizeExact(*s, r.box);
      GridComparison c = compareGrids(g, exact);
      EXPECT_GE(c.recall(), 0.9995) << res.x << "x" << res.y << "x" << res.z;
      EXPECT_GE(c.precision(), 0.9995) << res.x << "x" << res.y << "x" << res.z;
      // The hybrid: all fragment-parallel (cutoff 0), the default, all small ones triangle-parallel.
      for (float cutoff : {0.0f, 4.0f, 1e6f}) {
        r.hybridCutoff = cutoff;
        nlohmann::json hs;
        GridComparison h = compareGrids(voxelizeHybridGl(r, prof, hs), exact);
        EXPECT_GE(h.recall(), 0.9995) << "hybrid " << cutoff << " " << res.x << "x" << res.y << "x" << res.z;
        EXPECT_GE(h.precision(), 0.9995)
            << "hybrid " << cutoff << " " << res.x << "x" << res.y << "x" << res.z;
        const uint32_t small = hs.at("triangles_parallel"), large = hs.at("fragment_parallel");
        size_t triangles = 0;
        for (auto& m : s->meshes) triangles += m.triangles.size();
        EXPECT_EQ(small + large, uint32_t(triangles)) << "every triangle once";
        if (cutoff == 0.0f) {
          EXPECT_EQ(small, 0u);
        }
        if (cutoff == 1e6f && s == &hard) {
          EXPECT_GT(small, 150u);  // the random ones (≤ 512-cell boxes)
        }
      }
    }
  EXPECT_EQ(f.gl->errorCount(), 0);
}
}  // namespace vgi

namespace vgi {
// The automatic resolution rule (voxelize/grid_metrics.h): a planar surface
// crossing a cell with a disk of radius ¼ cell is found by a texel lattice of
// spacing ≤ √2/4 cell, i.e. ≥ 2√2 ≈ 2.83 texels per voxel. A plane at a generic
// angle that extends past the grid has no boundary inside it, so the rule must
// hold exactly there — and a sparser atlas must visibly fail it.
TEST(AtlasVoxelizer, ResolutionRuleFindsEveryInteriorCellOfAPlane) {
  GlFixture f;
  Scene s;
  Mesh& plane = test::addMesh(s, {}, {});
  glm::vec3 n = glm::normalize(glm::vec3(0.31f, 0.83f, 0.47f));
  shared::Basis b = shared::makeBasis(n);
  glm::vec3 c(0.25f, 0.25f, 0.5f);
  for (glm::vec2 q : {glm::vec2(-2, -2), glm::vec2(2, -2), glm::vec2(2, 2), glm::vec2(-2, 2)})
    plane.positions.push_back(c + q.x * b.t + q.y * b.b);
  plane.triangles = {{0, 1, 2}, {0, 2, 3}};
  VoxelizeRequest r = f.request(s, {64, 64, 128});
  r.atlasFootprint = 0.0f;         // the rule is about the points themselves
  r.box.origin = glm::vec3(0.0f);  // a fixed box of cubic cells inside the plane's extent
  r.box.extent = glm::vec3(0.5f, 0.5f, 1.0f);
  BinaryGrid interior = voxelizeExact(s, r.box, 0, 0, kInteriorShrink);
  for (float tpv : {kAutoTexelsPerVoxel, 1.0f}) {  // the default, and a sparser one
    r.texelsPerVoxel = tpv;
    Profiler prof(true);
    nlohmann::json stats;
    BinaryGrid got = voxelizeAtlasGl(r, prof, stats);
    GridComparison cmp = compareGrids(got, interior);
    if (tpv >= 2.0f * std::sqrt(2.0f) - 1e-4f)
      EXPECT_EQ(cmp.holes(), 0u) << "tpv " << tpv;
    else
      EXPECT_GT(cmp.holes(), 0u) << "tpv " << tpv << " should be too sparse";
  }
}
}  // namespace vgi

namespace vgi {
// A dynamic mesh's atlas is drawn once in object space and its points moved by the mesh's transform
// at insertion (no atlas drawn per frame): the GPU's moved points insert what the CPU inserts from the
// same points moved by glm, bit for bit, at a time the mesh has moved to, footprints included.
TEST(AtlasVoxelizer, AMovedMeshsKeptAtlasInsertsLikeTheCpu) {
  GlFixture f;
  Scene s = loadScene(test::writeMovingTriangleScene("kept"));
  VoxelizeRequest r = f.request(s, {64, 64, 128});
  r.time = 1.0f;
  Profiler prof(true);
  nlohmann::json stats;
  std::vector<AtlasSamples> points;
  BinaryGrid gpu = voxelizeAtlasGl(r, prof, stats, &points);
  BinaryGrid cpu(r.box);
  uint64_t valid = 0;  // every atlas texel holding a point (the dynamic mesh's listed ones among them)
  for (auto& atlas : points) {
    insertAtlasPoints(atlas, cpu);
    for (const glm::vec4& p : atlas.positions) valid += p.w != 0.0f ? 1 : 0;
  }
  EXPECT_EQ(gpu.words(), cpu.words());
  EXPECT_EQ(stats["points"].get<uint64_t>(), valid) << "each point inserted once";
  EXPECT_EQ(stats["dynamic_meshes"], 1);
  // The same time from frames: the kept atlas is moved again, not drawn.
  AtlasVoxelizer v(r, prof);
  v.voxelizeFrame(0.0f, prof);
  v.voxelizeFrame(1.0f, prof);
  EXPECT_EQ(v.readFrame().words(), gpu.words());
  prof.resolve(true);
  EXPECT_EQ(prof.callCounts()["atlas_render"], 8 + 8) << "each mesh's atlas once per voxelizer";
  EXPECT_EQ(f.gl->errorCount(), 0);
}

// Static meshes are voxelized once; every frame copies that grid and inserts the
// dynamic meshes: going forward and back in time reproduces the same grids, and
// each frame equals a fresh voxelization at its time.
TEST(AtlasVoxelizer, FramesReuseTheStaticGridWithoutStaleVoxels) {
  GlFixture f;
  Scene s = loadScene(test::writeMovingTriangleScene("moving"));
  VoxelizeRequest r = f.request(s, {64, 64, 128});
  Profiler prof(true);
  AtlasVoxelizer v(r, prof);
  EXPECT_EQ(v.stats()["static_meshes"], 7);
  EXPECT_EQ(v.stats()["dynamic_meshes"], 1);
  std::vector<BinaryGrid> frames;
  GlPyramid pyramid(r.box);
  for (float t : {0.0f, 1.0f, 0.0f}) {
    v.voxelizeFrame(t, prof);
    frames.push_back(v.readFrame());
    // The frame's pyramid, built on the GPU from the GPU grid (as `nearfield`
    // does per frame), equals the CPU build from the read-back grid.
    pyramid.build(v.frameGrid(), f.shaders);
    EXPECT_EQ(pyramid.read(), OrMipPyramid(frames.back()).words()) << "time " << t;
    EXPECT_EQ(pyramid.countLevel0(), frames.back().count());
  }
  EXPECT_EQ(frames[0].words(), frames[2].words());
  EXPECT_NE(frames[0].words(), frames[1].words());
  // The last frame copied the static grid back only over the cells the triangle could reach at
  // time 1 (a few rows of the 64 x 64 x 128 grid).
  const uint64_t restored = v.stats()["restored_cells"];
  EXPECT_GT(restored, 0u);
  EXPECT_LT(restored, r.box.cellCount() / 4);
  VoxelizeRequest at1 = r;
  at1.time = 1.0f;
  nlohmann::json stats;
  EXPECT_EQ(voxelizeAtlasGl(at1, prof, stats).words(), frames[1].words());
  prof.resolve(true);
  EXPECT_EQ(prof.callCounts()["copy"], 4);
  EXPECT_EQ(f.gl->errorCount(), 0);
}
}  // namespace vgi

namespace vgi {
// With value grids too: a voxelizer taken through several times holds at each the grid and the
// values of a fresh voxelizer's first frame (which copies everything), bit for bit — the static
// part copied back only where the dynamic mesh was at the frame before.
TEST(AtlasVoxelizer, FramesRestoreOnlyWhereTheDynamicMeshWasWithValues) {
  GlFixture f;
  Scene s = loadScene(test::writeMovingTriangleScene("moving-values"));
  VoxelizeRequest r = f.request(s, {64, 64, 128});
  r.valueGrids = {"normal", "albedo", "glossy"};
  Profiler prof(true);
  AtlasVoxelizer v(r, prof);
  bool first = true;
  for (float t : {0.0f, 1.0f, 0.5f, 0.0f}) {
    v.voxelizeFrame(t, prof);
    AtlasVoxelizer fresh(r, prof);
    fresh.voxelizeFrame(t, prof);
    EXPECT_EQ(v.readFrame().words(), fresh.readFrame().words()) << "time " << t;
    const ValueGrids a = v.readValues(), b = fresh.readValues();
    EXPECT_EQ(a.counts, b.counts) << "time " << t;
    ASSERT_EQ(a.means.size(), 3u);
    for (size_t c = 0; c < a.means.size(); ++c)
      EXPECT_TRUE(a.means[c] == b.means[c]) << a.channels[c] << " at time " << t;
    EXPECT_EQ(fresh.stats()["restored_cells"], r.box.cellCount());
    const uint64_t restored = v.stats()["restored_cells"];
    if (first)
      EXPECT_EQ(restored, r.box.cellCount());
    else
      EXPECT_LT(restored, r.box.cellCount() / 4) << "time " << t;
    first = false;
  }
  EXPECT_EQ(f.gl->errorCount(), 0);
}

// Multi-valued grids: built only on request, one value cell per binary cell,
// exact material values where a single surface fills a cell, unit normals on
// flat walls, glossy parameters round-tripping, frames copying the static part.
TEST(AtlasVoxelizer, MultiValuedGridsAverageTheirPoints) {
  GlFixture f;
  std::string path = testing::TempDir() + "/glossy.json";
  std::ofstream(path) << R"({ "meshes": [ {"path": "builtin:cornell"} ],
      "materials": { "white": {"albedo": [0.5, 0.5, 0.5], "ks": [0.3, 0.2, 0.1], "exponent": 50} } })";
  Scene s = loadScene(path);
  VoxelizeRequest r = f.request(s, {64, 64, 128});
  r.valueGrids = {"normal", "albedo", "glossy"};
  Profiler prof(true);
  AtlasVoxelizer v(r, prof);
  v.voxelizeFrame(0.0f, prof);
  BinaryGrid bin = v.readFrame();
  ValueGrids vals = v.readValues();
  ASSERT_EQ(vals.channels.size(), 3u);
  size_t withValues = 0;
  for (uint32_t z = 0; z < 128; ++z)
    for (uint32_t y = 0; y < 64; ++y)
      for (uint32_t x = 0; x < 64; ++x) {
        bool has = vals.counts[vals.cellIndex(x, y, z)] > 0;
        ASSERT_EQ(has, bin.test(x, y, z)) << x << "," << y << "," << z;
        withValues += has;
      }
  EXPECT_EQ(withValues, bin.count());
  // The middle of the red left wall (x at the top of the grid), and of the floor (y = 0).
  const auto& albedo = vals.channel("albedo");
  glm::vec4 red = albedo[vals.cellIndex(63, 32, 64)];
  EXPECT_NEAR(red.x, 0.63f, 2e-3f);
  EXPECT_NEAR(red.y, 0.065f, 2e-3f);
  const auto& normal = vals.channel("normal");
  glm::vec3 floorN(normal[vals.cellIndex(32, 0, 64)]);
  EXPECT_NEAR(std::abs(floorN.y), 1.0f, 1e-3f);
  glm::vec4 glossy = vals.channel("glossy")[vals.cellIndex(32, 0, 64)];  // floor: "white", overridden
  EXPECT_NEAR(glossy.x, 0.3f, 1e-3f);
  EXPECT_NEAR(glossy.z, 0.1f, 1e-3f);
  EXPECT_NEAR(glossy.w, 50.0f, 0.1f);
  EXPECT_NEAR(albedo[vals.cellIndex(32, 0, 64)].x, 0.5f, 1e-3f);
  // Only the requested grids: a request without them builds none.
  VoxelizeRequest plain = f.request(s, {64, 64, 128});
  AtlasVoxelizer p(plain, prof);
  EXPECT_TRUE(p.readValues().channels.empty());
  test::expectError([&] { vals.channel("radiance"); }, {"radiance"});
  test::expectError([] { parseValueChannels("normal,speed"); }, {"speed"});
  EXPECT_EQ(f.gl->errorCount(), 0);
}
}  // namespace vgi

namespace vgi {
// Far from the origin (issue 33, class 11): georeferenced-style coordinates, where a float's step is a
// large part of a cell. Each voxelizer of the registry finds the same share of the exact grid's cells as
// for the same scene at the origin, whether the coordinates are the mesh's own or come from its
// transform. (At 1e7 a float's step is 1: the unit box's corners are exact, its interior is not.)
TEST(Voxelizers, RecallFarFromTheOriginEqualsRecallAtTheOrigin) {
  GlFixture f;
  struct Case {
    const char* what;
    glm::vec3 lo, size, translate;
    bool quad;  // a tilted quad across the box (its cells are not all on grid planes), where floats hold it
  };
  const Case cases[] = {
      {"unit box at 1e7", {1e7f, 1e7f, 1e7f}, glm::vec3(1), glm::vec3(0), false},
      {"10 m cube at (5e5, 5e6)", {5e5f, 5e6f, 0}, glm::vec3(10), glm::vec3(0), true},
      {"10 m cube moved to (5e5, 5e6) by its transform", glm::vec3(0), glm::vec3(10), {5e5f, 5e6f, 0}, true}};
  for (const Case& c : cases) {
    auto scene = [&](bool far) {
      const glm::vec3 lo = far ? c.lo : glm::vec3(0);
      Scene s;
      test::addBox(s, lo, lo + c.size, test::addMaterial(s, glm::vec3(0.5f)));
      if (c.quad) {
        Mesh& q =
            test::addMesh(s, {{0.1f, 0.2f, 0.1f}, {0.9f, 0.3f, 0.2f}, {0.8f, 0.9f, 0.9f}, {0.2f, 0.7f, 0.8f}},
                          {{0, 1, 2}, {0, 2, 3}});
        for (glm::vec3& p : q.positions) p = lo + p * c.size;
      }
      if (far && c.translate != glm::vec3(0))
        for (Mesh& m : s.meshes) m.transform = glm::translate(glm::mat4(1.0f), c.translate);
      return s;
    };
    for (const VoxelizerInfo& v : voxelizerRegistry()) {
      double recall[2];
      for (bool far : {false, true}) {
        Scene s = scene(far);
        VoxelizeRequest r = f.request(s, {128, 128, 128});
        Profiler prof(true);
        nlohmann::json stats;
        GridComparison cmp = compareGrids(v.run(r, prof, stats), voxelizeExact(s, r.box));
        recall[far] = cmp.recall();
        EXPECT_GE(cmp.precision(), 0.999) << v.name << ", " << c.what << (far ? " (far)" : " (origin)");
      }
      EXPECT_GE(recall[1], recall[0] - 0.002)
          << v.name << ", " << c.what << ": recall at the origin " << recall[0];
      std::printf("  %-12s %-48s recall %.5f at the origin, %.5f far\n", v.name.c_str(), c.what, recall[0],
                  recall[1]);
    }
  }
  EXPECT_EQ(f.gl->errorCount(), 0);
}
}  // namespace vgi

namespace vgi {
// An animation keeps the static meshes' grid of a per-triangle voxelizer and voxelizes only the dynamic
// meshes again (the binary grid resource): for that, every voxelizer marked perTriangle gives a scene the
// OR of its static and its dynamic meshes' grids, word for word — here a box, a tilted quad through it
// and a moved, turned, finely split dynamic quad that crosses both, at a time between its keyframes.
TEST(Voxelizers, APerTriangleVoxelizersGridIsItsMeshesGridsOrEd) {
  GlFixture f;
  Scene s;
  test::addBox(s, glm::vec3(0.1f), glm::vec3(0.6f), test::addMaterial(s, glm::vec3(0.5f)));
  test::addMesh(s, {{0.0f, 0.2f, 0.1f}, {0.9f, 0.3f, 0.2f}, {0.8f, 0.9f, 0.9f}, {0.1f, 0.7f, 0.8f}},
                {{0, 1, 2}, {0, 2, 3}});
  std::vector<glm::vec3> p;
  std::vector<glm::uvec3> t;
  const int n = 24;  // an n×n grid of small triangles (the hybrid voxelizer's triangle-parallel path too)
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      p.push_back({0.5f * float(i) / n, 0.05f * std::sin(float(i + j)), 0.5f * float(j) / n});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const unsigned a = unsigned(j * (n + 1) + i);
      t.push_back({a, a + 1, a + unsigned(n) + 2});
      t.push_back({a, a + unsigned(n) + 2, a + unsigned(n) + 1});
    }
  Mesh& d = test::addMesh(s, p, t);
  d.dynamic = true;
  Keyframe k0, k1;
  k0.translation = {0.2f, 0.3f, 0.2f};
  k1.time = 1.0f;
  k1.translation = {0.4f, 0.5f, 0.1f};
  k1.rotation = glm::angleAxis(glm::radians(50.0f), glm::normalize(glm::vec3(1, 2, 0)));
  d.keyframes = {k0, k1};
  const Scene still = s.meshGeometry(false), moving = s.meshGeometry(true);
  ASSERT_EQ(still.meshes.size(), 2u);
  ASSERT_EQ(moving.meshes.size(), 1u);
  int checked = 0;
  for (const VoxelizerInfo& v : voxelizerRegistry()) {
    if (!v.perTriangle) continue;
    VoxelizeRequest r = f.request(s, {64, 64, 128}, 0.6f);
    Profiler prof(true);
    nlohmann::json stats;
    const BinaryGrid all = v.run(r, prof, stats);
    r.scene = &still;
    const BinaryGrid a = v.run(r, prof, stats);
    r.scene = &moving;
    const BinaryGrid b = v.run(r, prof, stats);
    uint64_t both = 0, onlyMoving = 0, differ = 0;
    for (size_t i = 0; i < all.words().size(); ++i) {
      const uint32_t x = a.words()[i], y = b.words()[i];
      both += uint64_t(__builtin_popcount(x & y));
      onlyMoving += uint64_t(__builtin_popcount(y & ~x));
      differ += all.words()[i] != (x | y) ? 1 : 0;
    }
    EXPECT_EQ(differ, 0u) << v.name << ": words that differ from the meshes' grids OR-ed";
    EXPECT_GT(both, 0u) << v.name << ": the dynamic quad crosses the static meshes' cells";
    EXPECT_GT(onlyMoving, 0u) << v.name;
    ++checked;
  }
  EXPECT_EQ(checked, 4) << "slicemap, conservative, hybrid, exact";
  EXPECT_EQ(f.gl->errorCount(), 0);
}
}  // namespace vgi
