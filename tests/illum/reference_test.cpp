// The Embree reference against analytic answers.
#include "illum/methods/reference.h"

#include <cmath>
#include <map>

#include "core/progress.h"
#include "core/scene_loader.h"
#include "illum/framework/method.h"
#include "illum/framework/sample_loop.h"
#include "illum/run/render_job.h"
#include "test_util.h"

namespace vgi {

namespace {
RenderResult renderRef(const Scene& s, std::vector<std::string> set, int w, int h, int spp, uint32_t seed = 1,
                       int threads = 0, std::vector<std::string> aovs = {}) {
  ParamSet p;
  for (auto& kv : set) p.setFromString(kv);
  auto m = referenceMethod().create(p, s);
  p.checkAllUsed("reference");
  RenderRequest r;
  r.aovs = aovs;
  r.scene = &s;
  r.width = w;
  r.height = h;
  r.spp = spp;
  r.seed = seed;
  r.threads = threads;
  r.progress = false;
  Profiler prof(false);
  return renderStill(*m, r, prof);
}

}  // namespace

using test::meanOf;

// Closed box, albedo ρ and emission Le everywhere: L = Le / (1 − ρ).
TEST(Reference, WhiteFurnace) {
  Scene s;
  int m = test::addMaterial(s, glm::vec3(0.5f, 0.8f, 0.2f), glm::vec3(1.0f));
  test::addBox(s, glm::vec3(-1), glm::vec3(1), m);
  s.camera.position = {0.2f, 0.1f, 0.3f};
  s.camera.target = {0.5f, -0.2f, 0.9f};
  s.camera.fovYDeg = 90;
  RenderResult r = renderRef(s, {"integrator=path", "maxdepth=10000"}, 24, 24, 64);
  EXPECT_NEAR(meanOf(r.image, 0), 1.0 / (1 - 0.5), 0.02 * 2.0);
  EXPECT_NEAR(meanOf(r.image, 1), 1.0 / (1 - 0.8), 0.03 * 5.0);
  EXPECT_NEAR(meanOf(r.image, 2), 1.0 / (1 - 0.2), 0.02 * 1.25);
}

TEST(Reference, UnoccludedPlaneHasAmbientOcclusionOne) {
  Scene s;
  test::addFloor(s, 100.0f, 0.0f, test::addMaterial(s, glm::vec3(0.5f)));
  s.camera.position = {0, 1, 0};
  s.camera.target = {0, 0, 0};
  s.camera.up = {0, 0, 1};
  s.camera.fovYDeg = 60;
  RenderResult r = renderRef(s, {"integrator=ao", "radius=5"}, 16, 16, 16);
  for (auto& p : r.image.pixels) ASSERT_EQ(p.x, 1.0f);
  // A box over the plane occludes: AO under and beside it drops below 1.
  test::addBox(s, glm::vec3(-0.5f, 0.02f, -0.5f), glm::vec3(0.5f, 0.3f, 0.5f), 0);
  s.camera.position = {0, 2, 0};
  RenderResult r2 = renderRef(s, {"integrator=ao", "radius=5"}, 16, 16, 16);
  EXPECT_LT(meanOf(r2.image, 0), 0.99);
}

// Point and spot lights over a Lambert plane: L = ρ/π · I(θ) cos θ / d².
TEST(Reference, DeltaLightsOnLambertPlaneMatchTheFormula) {
  for (LightType type : {LightType::Point, LightType::Spot}) {
    Scene s;
    const float rho = 0.6f, h = 0.5f;
    test::addFloor(s, 10.0f, 0.0f, test::addMaterial(s, glm::vec3(rho)));
    Light l;
    l.type = type;
    l.position = {0.3f, h, -0.2f};
    l.direction = {0, -1, 0};
    l.intensity = glm::vec3(2.0f);
    l.coneHalfAngleDeg = 60;
    l.falloff = 3;
    s.lights = {l};
    s.camera.position = {0, 3, 0};
    s.camera.target = {0, 0, 0};
    s.camera.up = {0, 0, 1};
    s.camera.fovYDeg = 50;
    const int W = 32;
    RenderResult r = renderRef(s, {"integrator=direct"}, W, W, 64);
    // Compare with the formula box-filtered over each pixel (8×8 sub-samples);
    // pixels crossing the spot's cone edge are skipped.
    const glm::vec3 fwd(0, -1, 0), right = glm::normalize(glm::cross(fwd, s.camera.up)),
                                   up = glm::cross(right, fwd);
    const float t = std::tan(glm::radians(25.0f));
    const float edge = std::cos(glm::radians(60.0f));
    auto radiance = [&](float sx, float sy, bool& nearEdge) {
      glm::vec3 d = glm::normalize(fwd + (2.0f * sx / W - 1) * t * right + (1 - 2.0f * sy / W) * t * up);
      glm::vec3 p = s.camera.position + d * (3.0f / -d.y);
      glm::vec3 toL = l.position - p;
      float d2 = glm::dot(toL, toL), cosSurf = toL.y / std::sqrt(d2), cosLight = cosSurf;
      float I = 2.0f;
      if (type == LightType::Spot) {
        nearEdge |= std::abs(cosLight - edge) < 0.05f;
        I = cosLight < edge ? 0.0f : 2.0f * std::pow(cosLight, 3.0f);
      }
      return rho / 3.14159265f * I * cosSurf / d2;
    };
    int compared = 0;
    double sumImage = 0, sumExpected = 0;
    for (int y = 0; y < W; ++y)
      for (int x = 0; x < W; ++x) {
        bool nearEdge = false;
        double expected = 0;
        for (int j = 0; j < 8; ++j)
          for (int i = 0; i < 8; ++i)
            expected += radiance(x + (i + 0.5f) / 8, y + (j + 0.5f) / 8, nearEdge) / 64.0;
        if (nearEdge) continue;
        // Per pixel: random jitter leaves Monte Carlo noise on the pixel integral.
        EXPECT_NEAR(r.image.at(x, y).x, expected, 0.06 * expected + 1e-6) << x << "," << y;
        sumImage += r.image.at(x, y).x;
        sumExpected += expected;
        ++compared;
      }
    EXPECT_GT(compared, W * W / 2);
    EXPECT_NEAR(sumImage / sumExpected, 1.0, 2e-3);  // no bias
  }
}

TEST(Reference, VarianceFallsAsOneOverSpp) {
  Scene s = loadScene("builtin:cornell");
  auto msd = [&](int spp) {
    Image a = renderRef(s, {"integrator=ao", "radius=0.2"}, 32, 32, spp, 11).image;
    Image b = renderRef(s, {"integrator=ao", "radius=0.2"}, 32, 32, spp, 12).image;
    double sum = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) sum += std::pow(double(a.pixels[i].x - b.pixels[i].x), 2);
    return sum / double(a.pixels.size());
  };
  double ratio = msd(4) / msd(64);
  EXPECT_GT(ratio, 16.0 * 0.7);
  EXPECT_LT(ratio, 16.0 * 1.4);
}

TEST(Reference, DeterministicForSeedWhateverTheThreadCount) {
  Scene s = loadScene("builtin:cornell");
  Image a = renderRef(s, {"integrator=path"}, 24, 20, 4, 5, 1).image;
  Image b = renderRef(s, {"integrator=path"}, 24, 20, 4, 5, 2).image;
  Image c = renderRef(s, {"integrator=path"}, 24, 20, 4, 6, 2).image;
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_NE(a.pixels, c.pixels);
}

// With an unbounded radius and a black environment, one near-field bounce is
// the path integrator truncated after two bounces (no emitters here).
TEST(Reference, NearFieldWithInfiniteRadiusEqualsTwoBouncePath) {
  Scene s = loadScene("builtin:cornell");
  Image nf = renderRef(s, {"integrator=nearfield", "radius=1000"}, 24, 24, 256, 3).image;
  Image pt = renderRef(s, {"integrator=path", "maxdepth=2", "rr_depth=10"}, 24, 24, 256, 4).image;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(meanOf(nf, c), meanOf(pt, c), 0.015 * meanOf(pt, c));
  // A vanishing radius leaves direct light only.
  Image tiny = renderRef(s, {"integrator=nearfield", "radius=1e-9"}, 24, 24, 4, 3).image;
  Image direct = renderRef(s, {"integrator=direct"}, 24, 24, 4, 3).image;
  for (size_t i = 0; i < tiny.pixels.size(); ++i) EXPECT_NEAR(tiny.pixels[i].x, direct.pixels[i].x, 1e-6f);
}

// The Cornell box with a Phong lobe on every surface (albedo scaled so that albedo + ks ≤ 1).
Scene glossyCornell(float ks) {
  Scene s = loadScene("builtin:cornell");
  for (Material& m : s.materials) {
    m.albedo *= 1.0f - ks;
    m.ks = glm::vec3(ks);
    m.exponent = 20.0f;
  }
  return s;
}

// glossy=first|direct leave out exactly the Phong lobes they name (a model-matched counterpart's
// omission): on a diffuse scene every mode is glossy=all bit for bit; on a glossy one the direct
// channel is glossy=all's (the same random numbers reach it; to the rounding of image − indirect), and glossy=direct's
// indirect channel is, in expectation, glossy=all's on the same scene with the lobes removed
// (every surface of the indirect light then reflects diffusely): whole-image means over seeds
// within 4 standard errors; glossy=first lies between.
TEST(Reference, GlossyModelsLeaveOutExactlyThePhongLobesTheyName) {
  const Scene diffuse = glossyCornell(0.0f), glossy = glossyCornell(0.3f);
  Scene lobesRemoved = glossy;
  for (Material& m : lobesRemoved.materials) m.ks = glm::vec3(0.0f);
  const int W = 24, H = 24;
  for (const char* integrator : {"integrator=path", "integrator=nearfield"}) {
    const Image all = renderRef(diffuse, {integrator}, W, H, 4, 3).image;
    for (const char* mode : {"glossy=first", "glossy=direct"})
      EXPECT_EQ(renderRef(diffuse, {integrator, mode}, W, H, 4, 3).image.pixels, all.pixels)
          << integrator << mode;
    std::map<std::string, std::vector<double>> indirect;  // per mode, one whole-image mean per seed
    const int seeds = 6;
    for (int seed = 1; seed <= seeds; ++seed) {
      const RenderResult a = renderRef(glossy, {integrator}, W, H, 32, seed, 0, {"direct", "indirect"});
      for (const char* mode : {"glossy=first", "glossy=direct"}) {
        const RenderResult m =
            renderRef(glossy, {integrator, mode}, W, H, 32, seed, 0, {"direct", "indirect"});
        // direct = image − indirect: the same to the rounding of that difference.
        const Image &md = m.aovs.at("direct"), &ad = a.aovs.at("direct");
        for (size_t i = 0; i < md.pixels.size(); ++i)
          for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(md.pixels[i][c], ad.pixels[i][c], 1e-5f * (m.image.pixels[i][c] + 1e-6f))
                << integrator << " " << mode << " pixel " << i;
        indirect[mode].push_back(meanOf(m.aovs.at("indirect"), 1));
      }
      indirect["all"].push_back(meanOf(a.aovs.at("indirect"), 1));
      const RenderResult d = renderRef(lobesRemoved, {integrator}, W, H, 32, seed + 100, 0, {"indirect"});
      indirect["lobes removed"].push_back(meanOf(d.aovs.at("indirect"), 1));
    }
    std::map<std::string, double> mean, se;
    for (auto& [mode, v] : indirect) {
      double var;
      test::meanAndVariance(v, mean[mode], var);
      se[mode] = std::sqrt(var / seeds);
    }
    std::printf("%s indirect (green): all %.5f, first %.5f, direct %.5f, lobes removed %.5f (se %.5f)\n",
                integrator, mean["all"], mean["glossy=first"], mean["glossy=direct"], mean["lobes removed"],
                se["glossy=direct"]);
    EXPECT_NEAR(mean["glossy=direct"], mean["lobes removed"],
                4.0 * std::hypot(se["glossy=direct"], se["lobes removed"]))
        << integrator;
    EXPECT_LT(mean["glossy=direct"], mean["glossy=first"]) << integrator;
    EXPECT_LT(mean["glossy=first"], mean["all"]) << integrator;
  }
}

TEST(Reference, ParametersOfOtherIntegratorsAreRejected) {
  Scene s = loadScene("builtin:cornell");
  ParamSet p;
  p.setFromString("integrator=ao");
  p.setFromString("maxdepth=3");
  test::expectError([&] { referenceMethod().create(p, s); }, {"maxdepth", "integrator=ao"});
  ParamSet docs;
  referenceMethod().create(docs, s);
  EXPECT_EQ(docs.docs().size(), 11u);                // all parameters documented
  EXPECT_FALSE(docs.resolved().contains("radius"));  // only the path integrator's resolved
  ParamSet q;
  q.setFromString("integrator=path");
  q.setFromString("radius=-1");
  test::expectError([&] { referenceMethod().create(q, s); }, {"radius"});
}

TEST(Reference, InterruptKeepsWhatWasAccumulated) {
  Scene s = loadScene("builtin:cornell");
  requestInterrupt();
  RenderResult r = renderRef(s, {"integrator=direct"}, 16, 16, 1000);
  resetInterrupt();
  EXPECT_TRUE(r.interrupted);
  EXPECT_LT(r.sppCompleted, 1000);
}

}  // namespace vgi

namespace vgi {
// A thousand samples through the framework's loop: every pixel ends with
// exactly the requested sample count.
TEST(Reference, ManyPassesAccumulateExactly) {
  Scene s = loadScene("builtin:cornell");
  ParamSet p;
  p.setFromString("integrator=ao");
  auto m = referenceMethod().create(p, s);
  RenderRequest r;
  r.scene = &s;
  r.width = 3;
  r.height = 2;
  r.spp = 1000;
  r.progress = false;
  Profiler prof(false);
  RenderResult res = renderStill(*m, r, prof);
  EXPECT_EQ(res.sppCompleted, 1000);
  EXPECT_FALSE(res.interrupted);
  for (auto& px : res.image.pixels) {
    EXPECT_GE(px.x, 0.0f);
    EXPECT_LE(px.x, 1.0f);
  }
}
}  // namespace vgi

namespace vgi {

// reference_gl is a second implementation of reference's estimators on the GL
// device: each integrator equals the CPU reference's within noise — over 8×8
// blocks of a 32×32 image, the difference of the block means over eight seeds
// stays within 5 standard errors (Welch; about 450 comparisons in all, so a
// false alarm is unlikely at that bound), and so does the whole image's mean
// (16 times less variance: a bias of a few per cent shows there) — in the image and, where the
// integrator splits it, the indirect output, on the Cornell box, the glossy
// box and CornellBox-Original (area lights: NEE + MIS) and Sibenik (textures,
// a spot light), where those are present. `glossy`: a glossy model (glossy=first|direct) on the
// glossy box alone (where it differs from glossy=all).
void expectGlEqualsCpu(const std::string& integrator, const std::string& glossy = "") {
  std::vector<std::string> scenes;
  if (glossy.empty()) scenes.push_back("builtin:cornell");
  // The project's scene files over ../shared/scenes, where those are present.
  const std::string projectScenes = std::string(VGI_TEST_DATA) + "/../../scenes/";
  if (!test::sharedScene("cornell-box/CornellBox-Glossy.obj").empty())
    scenes.push_back(projectScenes + "cornell-glossy.json");
  if (!glossy.empty() && scenes.empty()) GTEST_SKIP() << "the glossy Cornell box is absent";
  if (glossy.empty() && !test::sharedScene("cornell-box/CornellBox-Original.obj").empty())
    scenes.push_back(projectScenes + "cornell-original.json");
  if (glossy.empty() && !test::sharedScene("sibenik/sibenik.obj").empty())
    scenes.push_back(projectScenes + "sibenik.json");
  const bool split = integrator == "path" || integrator == "nearfield";
  const std::vector<std::string> channels =
      split ? std::vector<std::string>{"image", "indirect"} : std::vector<std::string>{"image"};
  const int size = 32, block = 8, seeds = 8;
  for (const std::string& scene : scenes) {
    std::map<std::string, std::vector<std::vector<double>>> gl, cpu;
    for (int seed = 1; seed <= seeds; ++seed) {
      RenderOptions o;
      o.scene = scene;
      o.width = o.height = size;
      o.progress = false;
      o.seed = uint32_t(seed);
      o.spp = 16;
      o.set = {"integrator=" + integrator};
      if (!glossy.empty()) o.set.push_back("glossy=" + glossy);
      if (split) o.aovs = {"indirect"};
      for (const char* method : {"reference_gl", "reference"}) {
        o.method = method;
        RenderOutput r = runRender(o);
        if (o.method == "reference_gl") {
          EXPECT_EQ(r.stats["gl_errors"].get<int>(), 0);
        }
        for (const std::string& c : channels) {
          const Image& img = c == "image" ? r.result.image : r.result.aovs.at(c);
          test::addBlockMeans(img, block, (o.method == "reference_gl" ? gl : cpu)[c]);
          test::addBlockMeans(img, size, (o.method == "reference_gl" ? gl : cpu)[c + " (whole image)"]);
        }
      }
    }
    for (const auto& [c, blocks] : gl) {
      double worstT = 0;
      for (size_t b = 0; b < gl[c].size(); ++b) {
        double ma, va, mb, vb;
        test::meanAndVariance(gl[c][b], ma, va);
        test::meanAndVariance(cpu[c][b], mb, vb);
        const double se = std::sqrt(va / seeds + vb / seeds);
        worstT = std::max(worstT, std::abs(ma - mb) / std::max(se, 1e-12));
        EXPECT_LT(std::abs(ma - mb), 5.0 * se + 1e-9)
            << scene << " " << integrator << " " << c << " block " << b << ": " << ma << " vs " << mb;
      }
      std::printf("%s: reference_gl vs reference integrator=%s%s, %s: worst |t| %.2f over %zu blocks\n",
                  scene.c_str(), integrator.c_str(), glossy.empty() ? "" : (" glossy=" + glossy).c_str(),
                  c.c_str(), worstT, gl[c].size());
    }
  }
}

TEST(ReferenceGl, AoEqualsTheCpuReferenceInBlockMeans) { expectGlEqualsCpu("ao"); }
TEST(ReferenceGl, PathEqualsTheCpuReferenceInBlockMeans) { expectGlEqualsCpu("path"); }
TEST(ReferenceGl, DirectEqualsTheCpuReferenceInBlockMeans) { expectGlEqualsCpu("direct"); }
TEST(ReferenceGl, NearFieldEqualsTheCpuReferenceInBlockMeans) { expectGlEqualsCpu("nearfield"); }
TEST(ReferenceGl, GlossyModelsEqualTheCpuReferenceInBlockMeans) {
  expectGlEqualsCpu("path", "direct");
  expectGlEqualsCpu("path", "first");
  expectGlEqualsCpu("nearfield", "direct");
}

// The same parameters as reference, read by one kit: voxel visibility, which
// runs on the CPU only, is refused by name.
TEST(ReferenceGl, RefusesVoxelVisibilityByName) {
  Scene s = loadScene("builtin:cornell");
  ParamSet p;
  p.setFromString("visibility=voxels");
  test::expectError([&] { findMethod("reference_gl").create(p, s); },
                    {"visibility", "voxels", "reference_gl", "CPU"});
  ParamSet docs;
  findMethod("reference_gl").create(docs, s);
  EXPECT_EQ(docs.docs().size(), 11u);  // the reference's parameters, all documented
}

}  // namespace vgi
