// avg (illum/methods/avg.cpp): the grid's construction against the exact voxelizer
// (single triangles of every orientation, including those perpendicular to a
// projection axis), the light tracing against Embree tracing of the same
// rays, shadow-map visibility against exact visibility, an occluder, and the
// closed sphere's bounces (analytic_sphere_test.cpp).
#include "illum/methods/avg.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>

#include "core/gl_context.h"
#include "core/gpu_scene.h"
#include "core/shader_library.h"
#include "render_util.h"
#include "shaders/shared/avg.glsl"
#include "test_util.h"
#include "voxelize/exact_voxelizer.h"

namespace vgi {

namespace {

double indirectMean(const RenderOutput& r) { return test::meanOf(r.result.aovs.at("indirect"), 1); }

}  // namespace

// One triangle at a time (in a scene whose box a second, fixed triangle
// spans): the cells whose count is 1 are exactly the cells the exact
// (triangle–box) voxelizer sets for it, each holding the triangle's unit
// normal and its albedo. Axis-aligned triangles (perpendicular to two
// projection axes) and random ones.
TEST(Avg, ASingleTrianglesSumsLandInTheCellsItOverlaps) {
  std::unique_ptr<GlContext> gl = GlContext::create();
  ShaderLibrary shaders;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.05f, 0.95f);
  std::vector<std::array<glm::vec3, 3>> tris = {
      // Off the cells' boundary planes (a plane on one is in both cells, a tie the float and exact tests may break apart).
      {glm::vec3(0.1f, 0.2f, 0.503f), glm::vec3(0.9f, 0.3f, 0.503f),
       glm::vec3(0.4f, 0.8f, 0.503f)},  // z = const
      {glm::vec3(0.517f, 0.1f, 0.2f), glm::vec3(0.517f, 0.9f, 0.3f),
       glm::vec3(0.517f, 0.4f, 0.8f)},  // x = const
      {glm::vec3(0.2f, 0.511f, 0.1f), glm::vec3(0.3f, 0.511f, 0.9f),
       glm::vec3(0.8f, 0.511f, 0.4f)},  // y = const
  };
  for (int i = 0; i < 5; ++i)
    tris.push_back({glm::vec3(u(rng), u(rng), u(rng)), glm::vec3(u(rng), u(rng), u(rng)),
                    glm::vec3(u(rng), u(rng), u(rng))});
  const glm::vec3 albedo(0.25f, 0.5f, 0.75f);
  for (const auto& t : tris) {
    Scene s;
    const int m = test::addMaterial(s, albedo);
    // The box: a tiny triangle at each corner of the unit cube keeps it fixed.
    Mesh& corners = test::addMesh(
        s, {{0, 0, 0}, {1e-3f, 0, 0}, {0, 1e-3f, 0}, {1, 1, 1}, {1 - 1e-3f, 1, 1}, {1, 1 - 1e-3f, 1}},
        {{0, 1, 2}, {3, 4, 5}});
    corners.material = m;
    Mesh& mesh = test::addMesh(s, {t[0], t[1], t[2]}, {{0, 1, 2}});
    mesh.material = m;
    const GridBox box = fitGridBox(s, glm::uvec3(32, 32, 128));
    AvgGrid avg(box, shaders);
    GpuScene gpu(s, 0.0f);
    avg.build(gpu);
    const std::vector<uint32_t> w = avg.read();
    Scene only = s;
    only.meshes.erase(only.meshes.begin());  // the triangle alone, voxelized exactly over the same box
    const BinaryGrid exact = voxelizeExact(only, box);
    const glm::vec3 n = glm::normalize(glm::cross(t[1] - t[0], t[2] - t[0]));
    int cells = 0;
    for (uint32_t z = 0; z < box.resolution.z; ++z)
      for (uint32_t y = 0; y < box.resolution.y; ++y)
        for (uint32_t x = 0; x < box.resolution.x; ++x) {
          const uint32_t b = shared::avgCellBase(glm::uvec3(x, y, z), box.resolution);
          const bool corner =
              (x == 0 && y == 0 && z == 0) ||
              (x + 1 == box.resolution.x && y + 1 == box.resolution.y && z + 1 == box.resolution.z);
          const uint32_t own = w[b + 6] - (corner ? 1u : 0u);
          ASSERT_EQ(own, exact.test(x, y, z) ? 1u : 0u)
              << "cell " << x << " " << y << " " << z << " of triangle " << (&t - tris.data());
          if (own == 0 || corner) continue;
          ++cells;
          const glm::vec3 ns = shared::avgMean(glm::ivec3(int(w[b]), int(w[b + 1]), int(w[b + 2])), 1);
          const glm::vec3 as = shared::avgMean(glm::ivec3(int(w[b + 3]), int(w[b + 4]), int(w[b + 5])), 1);
          ASSERT_NEAR(ns.x, n.x, 1e-4);
          ASSERT_NEAR(ns.y, n.y, 1e-4);
          ASSERT_NEAR(ns.z, n.z, 1e-4);
          ASSERT_NEAR(as.y, albedo.y, 1e-4);
        }
    EXPECT_GT(cells, 10);
  }
  EXPECT_EQ(gl->errorCount(), 0);
}

// The same rays and random numbers through the AVG and through the triangles
// (tracing=exact), both with exact visibility: the AVG's tracing error alone.
// On the Cornell box at 64³ it keeps the indirect light within 8 %.
TEST(Avg, TracingTheGridAgreesWithTracingTheTriangles) {
  auto run = [](const std::string& tracing) {
    return test::render("builtin:cornell", "avg",
                        {"tracing=" + tracing, "visibility=exact", "shadow_res=256"}, 48, 4, {"indirect"});
  };
  const RenderOutput grid = run("avg"), exact = run("exact");
  const double a = indirectMean(grid), e = indirectMean(exact);
  std::printf("avg tracing: indirect %.5f, exact tracing %.5f\n", a, e);
  EXPECT_NEAR(a / e, 1.0, 0.08);
  const int placedGrid = grid.stats["extra"]["vpls_placed"][0],
            placedExact = exact.stats["extra"]["vpls_placed"][0];
  EXPECT_NEAR(double(placedGrid) / placedExact, 1.0, 0.05) << "first hits: the same rays leave the open box";
}

// Shadow maps (hemicube, cube and paraboloid) against Embree occlusion rays from the
// same VPLs (their end lifted as the maps' centres are).
TEST(Avg, ShadowMapVisibilityAgreesWithExactVisibility) {
  auto run = [](const std::vector<std::string>& set) {
    std::vector<std::string> s = set;
    s.push_back("shadow_res=256");
    return indirectMean(test::render("builtin:cornell", "avg", s, 48, 4, {"indirect"}));
  };
  const double exact = run({"visibility=exact"}), hemicube = run({"shadow_map=hemicube"}),
               cube = run({"shadow_map=cube"}), para = run({"shadow_map=paraboloid"}),
               none = run({"visibility=none"});
  std::printf("avg visibility: exact %.5f, hemicube %.5f, cube %.5f, paraboloid %.5f, none %.5f\n", exact,
              hemicube, cube, para, none);
  EXPECT_NEAR(hemicube / exact, 1.0, 0.05);
  EXPECT_NEAR(cube / exact, 1.0, 0.05);
  EXPECT_NEAR(para / exact, 1.0, 0.07);  // the box's large triangles warp in paraboloids (measured 0.96)
  EXPECT_GT(none, 1.05 * exact) << "the blocks occlude some VPLs";
}

// The VPL maps draw the occluders (illum/occluders.h); the Cornell box is
// within their budget, so they are its own triangles and the image is the one
// the full scene gives (vpl_shadow_triangles=0), bit for bit.
TEST(Avg, OccludersWithinTheBudgetAreTheScene) {
  const RenderOutput occ = test::render("builtin:cornell", "avg", {}, 32, 2, {"indirect"});
  const RenderOutput full =
      test::render("builtin:cornell", "avg", {"vpl_shadow_triangles=0"}, 32, 2, {"indirect"});
  EXPECT_EQ(occ.result.image.pixels, full.result.image.pixels);
  EXPECT_EQ(occ.stats["extra"]["vpl_shadow_triangles"]["triangles"], 30);
  EXPECT_EQ(occ.stats["extra"]["vpl_shadow_triangles"]["tolerance"], 0.0);
  EXPECT_EQ(occ.stats["extra"]["vpl_shadow_triangles"]["budget_met"], true);
  EXPECT_NE(std::find(occ.stats["built"].begin(), occ.stats["built"].end(), "occluders"),
            occ.stats["built"].end());
  EXPECT_EQ(std::find(full.stats["built"].begin(), full.stats["built"].end(), "occluders"),
            full.stats["built"].end());
}

// Issue 64 §1: a VPL placed in a cell whose mean normal faces away from the ray. At the rim of the
// atrium's roof opening a cell holds the rim's inner face and the slab's underside; the sun's ray
// meets the inner face, but the mean of the two faces points down and inwards, away from the ray, and
// turning it round pointed it up into the slab: the VPL lit the slab's inside, and its shadow map,
// lifted into the slab, saw the inner face from behind — two pixels of 26 against 0.5 with exact
// visibility. The normal (shared/avg.glsl: avgVplNormal) faces the ray in every case, is the face
// the ray meets where the cell holds an edge or a corner, and the turned-round mean of a sheet.
TEST(Avg, AVplNormalFacesTheRayAndTheFaceItMeets) {
  const glm::vec3 d = glm::normalize(glm::vec3(0.35f, -1.0f, 0.2f));
  auto n = [&](glm::vec3 mean, glm::vec3 dir) { return shared::avgVplNormal(mean, dir); };
  // Front-facing means are kept (normalised).
  EXPECT_NEAR(glm::distance(n(glm::vec3(0.0f, 0.8f, 0.0f), d), glm::vec3(0, 1, 0)), 0.0f, 1e-6f);
  // A sheet seen from its other side: turned round.
  EXPECT_NEAR(glm::distance(n(glm::vec3(0.0f, -1.0f, 0.0f), d), glm::vec3(0, 1, 0)), 0.0f, 1e-6f);
  // The convex edge at the rim: the inner face (−x) the ray meets and the underside (−y) it cannot.
  const glm::vec3 rim = n(0.5f * (glm::vec3(-1, 0, 0) + glm::vec3(0, -1, 0)), d);
  EXPECT_LT(glm::dot(rim, d), 0.0f);
  EXPECT_GT(glm::dot(rim, glm::vec3(-1, 0, 0)), 0.9f) << rim.x << " " << rim.y << " " << rim.z;
  EXPECT_LT(rim.y, 0.2f) << "not into the slab";
  // A concave corner: a ray past the wall (+x normal) down onto the floor (+y).
  const glm::vec3 d2 = glm::normalize(glm::vec3(0.9f, -0.43f, 0.0f));
  const glm::vec3 floor = n(0.5f * (glm::vec3(1, 0, 0) + glm::vec3(0, 1, 0)), d2);
  EXPECT_LT(glm::dot(floor, d2), 0.0f);
  EXPECT_GT(floor.y, 0.9f);
  // An empty mean: back along the ray.
  EXPECT_NEAR(glm::distance(n(glm::vec3(0.0f), d), -d), 0.0f, 1e-6f);
  // Every mean: a unit normal facing the ray.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int i = 0; i < 1000; ++i) {
    const glm::vec3 m(u(rng), u(rng), u(rng)), r = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
    const glm::vec3 v = n(m, r);
    EXPECT_NEAR(glm::length(v), 1.0f, 1e-5f);
    EXPECT_LE(glm::dot(v, r), 1e-6f);
  }
}

// The same on the atrium (scenes/atrium.json: the rim against the sky, the sun behind it): the
// shadow maps give what exact visibility from the same VPLs gives, in the brightest pixel as in the
// mean, for four seeds (seed 2 had the two pixels of 26).
TEST(Avg, TheRimOfAnOpeningAgainstTheSkyHasNoHotSpot) {
  const std::string atrium = test::dataPath("../../scenes/atrium.json");
  for (uint32_t seed = 1; seed <= 4; ++seed) {
    auto run = [&](const std::vector<std::string>& set) {
      RenderOptions o = test::options(atrium, "avg", set, 160, 1, {"indirect"});
      o.width = 160;
      o.height = 90;
      o.seed = seed;
      const Image ind = runRender(o).result.aovs.at("indirect");
      double sum = 0, top = 0;
      for (const glm::vec3& p : ind.pixels) {
        const double v = double(p.x) + p.y + p.z;
        sum += v;
        top = std::max(top, v);
      }
      return std::pair<double, double>(sum / double(ind.width * ind.height), top);
    };
    const auto maps = run({"vpls=1024"}), exact = run({"vpls=1024", "visibility=exact"});
    std::printf("seed %u: maps mean %.4f max %.3f, exact visibility mean %.4f max %.3f\n", seed, maps.first,
                maps.second, exact.first, exact.second);
    EXPECT_NEAR(maps.first / exact.first, 1.0, 0.03) << "seed " << seed;
    EXPECT_LT(maps.second, 1.5 * exact.second) << "seed " << seed;
  }
}

// A budget the meshes cannot meet (the box's meshes are below kKeptTriangles: a box stays a box) is
// reported as not met — the render warns once, naming the parameter — and the maps draw what is left.
TEST(Avg, AnOccluderBudgetNotMetIsReported) {
  const RenderOutput r =
      test::render("builtin:cornell", "avg", {"vpl_shadow_triangles=1"}, 32, 1, {"indirect"});
  EXPECT_EQ(r.stats["extra"]["vpl_shadow_triangles"]["budget_met"], false);
  EXPECT_EQ(r.stats["extra"]["vpl_shadow_triangles"]["triangles"], 30);
}

// Bad parameters are refused naming the key.
TEST(Avg, BadParametersAreErrors) {
  test::expectError([] { test::render("builtin:cornell", "avg", {"grid=1"}, 8, 1); }, {"grid", "1"});
  test::expectError([] { test::render("builtin:cornell", "avg", {"shadow_map=dual"}, 8, 1); },
                    {"shadow_map", "dual", "cube"});
  test::expectError(
      [] {
        test::render("builtin:cornell", "avg", {"vpls=100000", "vpl_shadow_res=64"}, 8, 1);
      },
      {"vpls", "vpl_shadow_res", "atlas"});
  test::expectError([] { test::render("builtin:cornell", "avg", {"grid=1024"}, 8, 1); }, {"grid", "GiB"});
  test::expectError([] { test::render("builtin:cornell", "avg", {"march_step=nan"}, 8, 1); },
                    {"march_step", "nan"});
  test::expectError([] { test::render("builtin:cornell", "avg", {"vpl_shadow_triangles=-1"}, 8, 1); },
                    {"vpl_shadow_triangles", "-1"});
  test::expectError([] { test::render("builtin:cornell", "avg", {"vpl_shadow_tolerance=0"}, 8, 1); },
                    {"vpl_shadow_tolerance", "0"});
}

// Issue 64 §3: a VPL method's expected value must not depend on how many VPLs it draws. The
// chains' R2 points were left unrotated in sample 0, so every seed drew the same first VPLs; on an
// atrium lit through its opening (scenes/atrium.json: few of a directional light's VPLs enter it)
// 64 VPLs then gave 1.26–1.54 (three seeds) against 0.88–0.92 for 1024 of the indirect energy of
// the exact, in the same pixels for every seed. The indirect light's mean over seeds at one sample,
// 64 chains against 1024, within three standard errors (and 2 %); and the 64 chains' seeds must
// differ (they did only in their bounces).
namespace {
struct OverSeeds {
  double mean = 0, standardError = 0;
};
OverSeeds indirectOverSeeds(const std::string& scene, std::vector<std::string> set, int vpls, int seeds) {
  set.push_back("vpls=" + std::to_string(vpls));
  std::vector<double> v;
  for (int seed = 1; seed <= seeds; ++seed) {
    RenderOptions o = test::options(scene, "avg", set, 32, 1, {"indirect"});
    o.seed = uint32_t(seed);
    const RenderOutput out = runRender(o);
    const Image& ind = out.result.aovs.at("indirect");
    v.push_back(test::meanOf(ind, 0) + test::meanOf(ind, 1) + test::meanOf(ind, 2));
  }
  OverSeeds r;
  double var = 0;
  test::meanAndVariance(v, r.mean, var);
  r.standardError = std::sqrt(var / double(seeds));
  return r;
}
void expectTheSameEnergy(const std::string& scene, const std::vector<std::string>& set) {
  const OverSeeds few = indirectOverSeeds(scene, set, 64, 24), many = indirectOverSeeds(scene, set, 1024, 4);
  std::printf("%s: 64 VPLs %.5f ± %.5f, 1024 VPLs %.5f ± %.5f\n", scene.c_str(), few.mean, few.standardError,
              many.mean, many.standardError);
  ASSERT_GT(many.mean, 0.0);
  EXPECT_GT(few.standardError, 0.02 * few.mean) << "the seeds draw different first VPLs";
  EXPECT_NEAR(few.mean, many.mean,
              3.0 * std::hypot(few.standardError, many.standardError) + 0.02 * many.mean);
}
}  // namespace

TEST(Avg, TheIndirectEnergyDoesNotFollowTheVplCount) {
  expectTheSameEnergy(test::dataPath("../../scenes/atrium.json"), {});
}

TEST(Avg, TheIndirectEnergyDoesNotFollowTheVplCountOnSibenik) {
  if (test::sharedScene("sibenik/sibenik.obj").empty()) GTEST_SKIP() << "../shared/scenes not present";
  // Without visibility (what the count changed is where the VPLs are, not what they see): 64 chains'
  // maps of Sibenik's 22 k occluders are cheap, 1024 chains' are not.
  expectTheSameEnergy(test::dataPath("../../scenes/sibenik.json"), {"visibility=none"});
}

}  // namespace vgi
