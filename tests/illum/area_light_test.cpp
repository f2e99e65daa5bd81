// Area lights (emissive meshes, core/emitters.h) in every method: the emitter
// sampling itself, an analytic case (a Lambert floor under a one-sided square
// emitter, whose irradiance Sparrow's corner formula gives exactly) for the
// reference's three strategies and for the GL methods' spot-light samples,
// and CornellBox-Original.obj with its own light quad.
#include <cmath>
#include <fstream>
#include <map>

#include "core/emitters.h"
#include "core/image_metrics.h"
#include "core/scene_loader.h"
#include "render_util.h"
#include "test_util.h"

namespace vgi {

using test::meanOf;
using test::render;

namespace {

// A floor (albedo 0.5, y = 0, ±10) and a square emitter (side 2a, height h,
// Le = 2, albedo 0) facing down; the emitter's winding is counter-clockwise
// seen from below. Written as OBJ + MTL, as a user's scene would be.
constexpr float kRho = 0.5f, kHalf = 0.5f, kHeight = 1.0f, kLe = 2.0f;
std::string writeEmitterScene(const std::string& name, const std::string& camera, bool twoSided = false) {
  const std::string dir = testing::TempDir();
  std::ofstream(dir + "/" + name + ".mtl")
      << "newmtl floor\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0 0 0\nKe 2 2 2\n";
  std::ofstream(dir + "/" + name + ".obj") << "mtllib " << name << ".mtl\n"
                                           << "v -10 0 -10\nv 10 0 -10\nv 10 0 10\nv -10 0 10\n"
                                           << "v -0.5 1 -0.5\nv 0.5 1 -0.5\nv 0.5 1 0.5\nv -0.5 1 0.5\n"
                                           << "usemtl floor\nf 1 4 3\nf 1 3 2\n"  // up
                                           << "usemtl lamp\nf 5 6 7\nf 5 7 8\n";  // down
  const std::string path = dir + "/" + name + ".json";
  std::ofstream(path) << R"({ "meshes": [ {"path": ")" << dir << "/" << name << R"(.obj"} ], )"
                      << R"("two_sided_emission": )" << (twoSided ? "true" : "false") << ", " << camera
                      << " }";
  return path;
}
// Looking straight down at the floor's centre from below the emitter (a 6° view).
const char* kFloorCamera =
    R"("camera": {"position": [0, 0.5, 0], "target": [0, 0, 0], "up": [0, 0, 1], "fov_deg": 6})";

// Irradiance at floor point (x, z) from the emitter: Sparrow's form factor of
// a rectangle with a corner above the point, summed over the four corner
// rectangles (the point lies under the emitter); E = π·Le·F.
double irradiance(double x, double z) {
  auto corner = [](double a, double b) {
    const double X = a / kHeight, Y = b / kHeight, sx = std::sqrt(1 + X * X), sy = std::sqrt(1 + Y * Y);
    return (X / sx * std::atan(Y / sx) + Y / sy * std::atan(X / sy)) / (2 * M_PI);
  };
  const double F = corner(kHalf - x, kHalf - z) + corner(x + kHalf, kHalf - z) +
                   corner(kHalf - x, z + kHalf) + corner(x + kHalf, z + kHalf);
  return M_PI * kLe * F;
}

// The floor's radiance averaged over the image (each pixel's centre ray).
double expectedFloorMean(int size) {
  const double t = std::tan(3.0 * M_PI / 180.0);
  double sum = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      // Camera right = fwd × up = (0,-1,0) × (0,0,1) = (-1, 0, 0); up = (0, 0, 1) on screen.
      const double px = (2.0 * (x + 0.5) / size - 1) * t * 0.5, pz = (1 - 2.0 * (y + 0.5) / size) * t * 0.5;
      sum += kRho / M_PI * irradiance(-px, pz);
    }
  return sum / (size * size);
}

}  // namespace

TEST(Emitters, SamplingFollowsPowerAndCoversEachTriangleUniformly) {
  Scene s;
  const int dim = test::addMaterial(s, glm::vec3(0.5f), glm::vec3(1.0f));
  const int bright = test::addMaterial(s, glm::vec3(0.5f), glm::vec3(3.0f));
  test::addFloor(s, 1.0f, 0.0f, dim);                                     // area 4, power ∝ 4
  test::addFloor(s, 0.5f, 1.0f, bright);                                  // area 1, power ∝ 3
  test::addFloor(s, 2.0f, -1.0f, test::addMaterial(s, glm::vec3(0.5f)));  // not an emitter
  const Emitters e(s, flatten(s));
  ASSERT_EQ(e.size(), 4u);
  EXPECT_EQ(e.emitterOfTriangle(4), -1);
  double pdfSum = 0;
  for (size_t i = 0; i < e.size(); ++i) pdfSum += e.pdfArea(int(i)) * e.triangles()[i].area;
  EXPECT_NEAR(pdfSum, 1.0, 1e-6);
  // Stratified u: the share of each mesh is its power share, and the points
  // of one triangle fill it uniformly: all inside, their mean the centroid,
  // and a quarter of them in the half-scaled corner triangle at each vertex.
  const int n = 256;
  std::map<int, int> perMesh;
  std::vector<glm::dvec3> centroid(e.size(), glm::dvec3(0.0));
  std::vector<int> count(e.size(), 0);
  std::vector<glm::ivec3> corners(e.size(), glm::ivec3(0));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      EmitterSample es = e.sample({(i + 0.5f) / n, (j + 0.5f) / n});
      ASSERT_GE(es.emitter, 0);
      EXPECT_FLOAT_EQ(es.pdfArea, e.pdfArea(es.emitter));
      perMesh[e.triangles()[size_t(es.emitter)].mesh]++;
      const size_t t = size_t(es.emitter);
      centroid[t] += glm::dvec3(es.p);
      count[t]++;
      // Barycentrics of the point (the triangles lie in planes y = const).
      const EmitterTriangle& tri = e.triangles()[t];
      const glm::dvec2 d(es.p.x - tri.p0.x, es.p.z - tri.p0.z), a(tri.e1.x, tri.e1.z), b(tri.e2.x, tri.e2.z);
      const double det = a.x * b.y - a.y * b.x;
      const double b1 = (d.x * b.y - d.y * b.x) / det, b2 = (a.x * d.y - a.y * d.x) / det, b0 = 1 - b1 - b2;
      ASSERT_GE(std::min({b0, b1, b2}), -1e-5) << "outside triangle " << t;
      corners[t] += glm::ivec3(b0 > 0.5 ? 1 : 0, b1 > 0.5 ? 1 : 0, b2 > 0.5 ? 1 : 0);
    }
  EXPECT_NEAR(perMesh[0] / double(n * n), 4.0 / 7.0, 2.0 / n);
  EXPECT_NEAR(perMesh[1] / double(n * n), 3.0 / 7.0, 2.0 / n);
  for (size_t t = 0; t < e.size(); ++t) {
    const EmitterTriangle& tri = e.triangles()[t];
    const glm::dvec3 c = glm::dvec3(tri.p0) + (glm::dvec3(tri.e1) + glm::dvec3(tri.e2)) / 3.0;
    EXPECT_LT(glm::length(centroid[t] / double(count[t]) - c), 0.01) << t;
    for (int v = 0; v < 3; ++v) EXPECT_NEAR(corners[t][v] / double(count[t]), 0.25, 0.01) << t << " " << v;
  }
  // The spot light of a point carries Le·A/p: here Le·(total area) per unit Le.
  std::vector<Light> spots = e.spotLights({0.1f, 0.3f});
  ASSERT_EQ(spots.size(), 1u);
  EXPECT_EQ(spots[0].coneHalfAngleDeg, 90.0f);
  EXPECT_NEAR(spots[0].intensity.x, 7.0, 1e-4);  // 1·4/(4/7)
}

TEST(Emitters, OneSidedEmitsOnTheWindingSideTwoSidedOnBoth) {
  Scene s;
  test::addFloor(s, 1.0f, 0.0f, test::addMaterial(s, glm::vec3(0.5f), glm::vec3(1.0f)));
  const glm::vec3 n = Emitters(s, flatten(s)).triangles()[0].normal;
  for (bool two : {false, true}) {
    s.twoSidedEmission = two;
    const Emitters e(s, flatten(s));
    EXPECT_EQ(e.radianceToward(0, n), glm::vec3(1.0f));
    EXPECT_EQ(e.radianceToward(0, -n), glm::vec3(two ? 1.0f : 0.0f));
    EXPECT_EQ(e.spotLights({0.5f, 0.5f}).size(), two ? 2u : 1u);
    EXPECT_NEAR(e.power(0).x, M_PI * 2.0 * (two ? 2 : 1), 1e-4);  // π·Le·A per side
  }
}

TEST(Emitters, SequenceIsLowDiscrepancyAndSeeded) {
  const int n = 64;
  int cells[4][4] = {};
  for (int k = 0; k < n; ++k) {
    glm::vec2 u = emitterSequence(k, 1);
    ASSERT_GE(u.x, 0.0f);
    ASSERT_LT(u.x, 1.0f);
    ASSERT_GE(u.y, 0.0f);
    ASSERT_LT(u.y, 1.0f);
    cells[int(u.x * 4)][int(u.y * 4)]++;
  }
  for (auto& row : cells)
    for (int c : row) EXPECT_NEAR(c, n / 16, 2);  // R2 fills every cell evenly
  EXPECT_NE(emitterSequence(3, 1), emitterSequence(3, 2));
}

TEST(AreaLights, ReferenceMatchesTheSquareEmitterFormulaWithEachStrategy) {
  const std::string path = writeEmitterScene("square_emitter_ref", kFloorCamera);
  const int size = 16;
  const double expected = expectedFloorMean(size);
  for (const char* strategy : {"mis", "light", "brdf"}) {
    RenderOutput r =
        render(path, "reference", {"integrator=direct", std::string("emitter_sampling=") + strategy}, size,
               strategy == std::string("brdf") ? 2048 : 256);
    EXPECT_NEAR(meanOf(r.result.image), expected, 0.01 * expected) << strategy;
    EXPECT_EQ(r.stats["extra"]["emitter_triangles"], 2) << strategy;
  }
}

TEST(AreaLights, GlDirectConvergesToTheSquareEmitterFormula) {
  const std::string path = writeEmitterScene("square_emitter_gl", kFloorCamera);
  const int size = 16;
  const double expected = expectedFloorMean(size);
  // One emitter point (R2) per frame: a quasi-Monte Carlo estimate whose error
  // falls about as 1/N (measured: +3 % at 16 frames, +1 % at 64, +0.35 % at
  // 256, −0.04 % at 1024), i.e. no bias.
  RenderOutput r64 = render(path, "direct", {"shadow_res=128"}, size, 64);
  RenderOutput r = render(path, "direct", {"shadow_res=128"}, size, 256);
  EXPECT_EQ(r.stats["gl_errors"], 0);
  const double e64 = std::abs(meanOf(r64.result.image) / expected - 1),
               e256 = std::abs(meanOf(r.result.image) / expected - 1);
  EXPECT_LT(e64, 0.02);
  EXPECT_LT(e256, 0.006);
  EXPECT_LT(e256, 0.6 * e64);
  // The light maps follow the sample: they are a per-sample pass.
  bool perSample = false;
  for (auto& p : r.stats["sample_passes"]) perSample |= p == "shadow_maps";
  EXPECT_TRUE(perSample) << r.stats["sample_passes"].dump();
}

TEST(AreaLights, OneSidedEmitterIsBlackFromBehindInEveryRenderer) {
  const char* below =
      R"("camera": {"position": [0, 0.5, 0], "target": [0, 1, 0], "up": [0, 0, 1], "fov_deg": 20})";
  const char* above =
      R"("camera": {"position": [0, 2, 0], "target": [0, 1, 0], "up": [0, 0, 1], "fov_deg": 20})";
  for (bool two : {false, true}) {
    const std::string b = writeEmitterScene(two ? "two_below" : "one_below", below, two);
    const std::string a = writeEmitterScene(two ? "two_above" : "one_above", above, two);
    for (const char* method : {"direct", "reference"}) {
      std::vector<std::string> set;
      if (method == std::string("reference")) set = {"integrator=direct"};
      // The view is filled by the emitter (albedo 0): exactly Le from the front.
      EXPECT_NEAR(meanOf(render(b, method, set, 8, 4).result.image), kLe, 1e-4) << method;
      EXPECT_NEAR(meanOf(render(a, method, set, 8, 4).result.image), two ? kLe : 0.0, 1e-4) << method << two;
    }
  }
}

// The standard Cornell box with its own light quad (no delta light).
TEST(AreaLights, CornellBoxOriginalGlDirectMatchesTheReferenceAt64Frames) {
  const std::string scene = test::sharedScene("cornell-box/CornellBox-Original.obj");
  if (scene.empty()) GTEST_SKIP() << "shared scenes absent";
  RenderOutput gl = render(scene, "direct", {}, 64, 64);
  RenderOutput ref = render(scene, "reference", {"integrator=direct"}, 64, 1024);
  EXPECT_EQ(gl.stats["gl_errors"], 0);
  ImageDiff d = compareImages(gl.result.image, ref.result.image);
  EXPECT_LT(d.relMse, 0.01);
  // 64 emitter points: +1.5 % energy (measured; 256 frames −0.07 %, 1024 −0.02 %).
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(d.energyRgb[c], 1.0, 0.025) << c;
}

TEST(AreaLights, CornellBoxOriginalNearFieldIndirectMatchesTheReference) {
  const std::string scene = test::sharedScene("cornell-box/CornellBox-Original.obj");
  if (scene.empty()) GTEST_SKIP() << "shared scenes absent";
  RenderOutput gl = render(scene, "nearfield", {"shadow_res=256"}, 48, 16, {"indirect"});
  RenderOutput ref = render(scene, "reference", {"integrator=nearfield"}, 48, 256, {"indirect"});
  EXPECT_EQ(gl.stats["gl_errors"], 0);
  const Image& a = gl.result.aovs.at("indirect");
  const Image& b = ref.result.aovs.at("indirect");
  ASSERT_GT(meanOf(b), 0.0);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(meanOf(a, c) / meanOf(b, c), 1.0, 0.08) << c;
}

// NEE + MIS against BRDF sampling alone: 16 spp against a 4096-spp render.
TEST(AreaLights, CornellBoxOriginalMisCutsTheReferenceErrorTenfoldWithoutBias) {
  const std::string scene = test::sharedScene("cornell-box/CornellBox-Original.obj");
  if (scene.empty()) GTEST_SKIP() << "shared scenes absent";
  const int size = 32;
  const Image truth = render(scene, "reference", {}, size, 4096).result.image;
  auto relMse = [&](const char* strategy) {
    RenderOutput r = render(scene, "reference", {std::string("emitter_sampling=") + strategy}, size, 16);
    return compareImages(r.result.image, truth).relMse;
  };
  const double mis = relMse("mis"), brdf = relMse("brdf");
  EXPECT_GT(brdf / mis, 10.0) << "brdf " << brdf << " mis " << mis;
  // No bias: the image means of independent runs (seeds) agree within noise (Welch's t).
  auto means = [&](const char* strategy) {
    std::vector<double> m;
    for (uint32_t seed = 1; seed <= 6; ++seed) {
      RenderOptions o;
      o.scene = scene;
      o.method = "reference";
      o.set = {std::string("emitter_sampling=") + strategy};
      o.width = o.height = size;
      o.spp = 64;
      o.seed = seed;
      o.progress = false;
      m.push_back(meanOf(runRender(o).result.image, 1));
    }
    return m;
  };
  double mm, vm, mb, vb;
  test::meanAndVariance(means("mis"), mm, vm);
  test::meanAndVariance(means("brdf"), mb, vb);
  const double t = (mm - mb) / std::sqrt(vm / 6 + vb / 6);
  EXPECT_LT(std::abs(t), 4.0) << "mis " << mm << " brdf " << mb;
}

}  // namespace vgi
