// The GL `direct` module against its exact counterpart, reference
// integrator=direct: the difference is the shadow-map error.
#include <algorithm>
#include <fstream>

#include "core/image_metrics.h"
#include "core/scene_loader.h"
#include "illum/run/render_job.h"
#include "render_util.h"
#include "test_util.h"

namespace vgi {

using test::render;

TEST(DirectModule, MatchesTheEmbreeDirectReferenceOnTheCornellBox) {
  RenderOutput gl = render("builtin:cornell", "direct", {}, 96, 16);
  RenderOutput ref = render("builtin:cornell", "reference", {"integrator=direct"}, 96, 16);
  EXPECT_EQ(gl.stats["gl_errors"], 0);
  ImageDiff d = compareImages(gl.result.image, ref.result.image);
  EXPECT_LT(d.relMse, 0.01);
  EXPECT_GT(d.ssim, 0.95);
  for (const char* key :
       {"method", "scene", "width", "height", "spp", "gl_renderer", "timings_ms", "total_ms", "params"})
    EXPECT_TRUE(gl.stats.contains(key)) << key;
  EXPECT_TRUE(gl.stats["timings_ms"].contains("shade"));
}

// An open scene exercises the point-light cube maps from outside a box and the
// directional light's orthographic map.
TEST(DirectModule, PointAndDirectionalShadowsMatchTheReference) {
  std::string path = testing::TempDir() + "/open.json";
  std::ofstream(path) << R"({
    "meshes": [ {"path": ")"
                      << test::dataPath("open_scene.obj") << R"("} ],
    "lights": [ {"type": "point", "position": [1.5, 2.5, 1.0], "intensity": [3, 3, 3]},
                {"type": "directional", "direction": [-0.4, -1, -0.3], "irradiance": [0.6, 0.5, 0.4]},
                {"type": "spot", "position": [-1, 2, 1], "direction": [0.3, -1, -0.3], "intensity": 4,
                 "cone_deg": 35, "falloff": 2} ],
    "camera": {"position": [3, 3, 5], "target": [0, 0.3, 0], "fov_deg": 40} })";
  RenderOutput gl = render(path, "direct", {}, 96, 16);
  RenderOutput ref = render(path, "reference", {"integrator=direct"}, 96, 16);
  ImageDiff d = compareImages(gl.result.image, ref.result.image);
  EXPECT_LT(d.relMse, 0.01);
  // The point light gets a cube; the 35° spot and the directional light one face each.
  EXPECT_EQ(gl.stats["extra"]["light_maps"]["cube"], 1);
  EXPECT_EQ(gl.stats["extra"]["light_maps"]["single_face"], 2);
  EXPECT_EQ(gl.stats["extra"]["light_maps"]["faces"], 8);
}

// The tall box's front face is lit at grazing incidence (the light lies
// almost in its plane), stands on the floor and sits beside a back face at
// its right silhouette:
// one un-jittered frame must match the exact direct light on every pixel of
// it. Shadow acne (slope-scaled bias capped at 5 texels: dark dots, −19 %)
// and depth ties with the back face (a [−1, 1] depth range with a tiny near
// plane: column 263 black) both failed this, and so did trusting the
// receiver's plane beyond the face (a dark band at its foot).
TEST(DirectModule, GrazingLitFaceHasNoAcneAndSilhouettesKeepTheFrontFace) {
  RenderOutput gl = render("builtin:cornell", "direct", {}, 512, 1);
  RenderOutput ref = render("builtin:cornell", "reference", {"integrator=direct"}, 512, 2);
  int checked = 0;
  // Above y = 325 the whole face up to its right silhouette; below, its left
  // part down to the foot (the short box is in front on the right), where the
  // floor along a neighbouring texel's ray must not shadow it.
  for (int y = 222; y <= 428; ++y)
    for (int x = 160; x <= (y < 325 ? 263 : 240); ++x) {
      // (The edge crosses pixel 263 at ~263.99: its jittered reference samples
      // may see the wall behind, so it is held to its neighbour's value.)
      const float a = gl.result.image.at(x, y).x, b = ref.result.image.at(std::min(x, 262), y).x;
      ASSERT_GT(b, 0.003f) << "not the lit front face at " << x << "," << y;
      ASSERT_NEAR(a, b, 0.05f * b) << "at " << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, 10000);
}

// Sibenik (the VGI paper's scene; skipped without ../shared): thin ledges,
// smooth-shaded columns and grazing light. The session-3 shadow test (slope-
// scaled bias up to 5 texels, normal offset 0.25) measured SSIM 0.949 here:
// light leaking under the ledges, contact shadows lost on the columns.
TEST(DirectModule, SibenikShadowsMatchTheReference) {
  if (test::sharedScene("sibenik/sibenik.obj").empty()) GTEST_SKIP() << "../shared/scenes not present";
  const std::string scene = std::string(VGI_TEST_DATA) + "/../../scenes/sibenik.json";
  RenderOutput gl = render(scene, "direct", {}, 192, 16);
  RenderOutput ref = render(scene, "reference", {"integrator=direct"}, 192, 16);
  ImageDiff d = compareImages(gl.result.image, ref.result.image);
  EXPECT_LT(d.relMse, 0.0013);  // measured 0.00116 (session 3: 0.00158)
  EXPECT_GT(d.ssim, 0.965);     // measured 0.9778 (session 3: 0.9493)
}

TEST(DirectModule, BadParametersAreErrors) {
  test::expectError([] { render("builtin:cornell", "direct", {"shadow_res=4"}, 8, 1); }, {"shadow_res", "4"});
  test::expectError([] { render("builtin:cornell", "direct", {"shadowres=512"}, 8, 1); }, {"shadowres=512"});
  test::expectError([] { render("builtin:cornell", "nosuch", {}, 8, 1); }, {"nosuch", "direct", "reference"});
  test::expectError([] { render("builtin:cornell", "direct", {}, 8, 0); }, {"--spp", "0"});
}

}  // namespace vgi

namespace vgi {
// A lat-long environment whose texels encode their own (u, v): the reference
// (CPU lookup) and the GL module (texture lookup) must agree on orientation, and
// straight up must read the top row.
TEST(DirectModule, EnvironmentMapOrientationMatchesTheReference) {
  Image env(64, 32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) env.at(x, y) = glm::vec3((x + 0.5f) / 64, 1.0f - (y + 0.5f) / 32, 0.25f);
  std::string dir = testing::TempDir();
  writeImage(env, dir + "/env_uv.exr");
  std::ofstream(dir + "/env_scene.json") << R"({
    "meshes": [ {"path": ")" << test::dataPath("triangle.gltf")
                                         << R"("} ],
    "lights": [ {"type": "point", "position": [0, 0, 5], "intensity": 1} ],
    "environment": {"map": "env_uv.exr", "scale": 2},
    "camera": {"position": [0, 0, 0], "target": [0.3, 0.4, -1], "fov_deg": 120} })";
  Scene s = loadScene(dir + "/env_scene.json");
  EXPECT_NEAR(s.environmentRadiance({0, 1, 0}).y, 2.0f * (1.0f - 0.5f / 32), 1e-4f);  // zenith: top row
  EXPECT_NEAR(s.environmentRadiance({0, 0, -1}).x, 2.0f * 0.5f, 0.02f);               // −z: u = ½
  RenderOutput gl = render(dir + "/env_scene.json", "direct", {}, 48, 4);
  RenderOutput ref = render(dir + "/env_scene.json", "reference", {"integrator=direct"}, 48, 16);
  EXPECT_LT(compareImages(gl.result.image, ref.result.image).relMse, 0.01);
}
}  // namespace vgi
