// The GL `nearfield` module (VGI §5.1) against exact answers: an analytic
// open scene (every ray escapes: indirect = albedo × environment exactly),
// its exact Embree counterpart on the Cornell box, and the module framework
// (parameters, needs/built, AOVs, tracer selection).
#include <algorithm>
#include <fstream>

#include "core/image_metrics.h"
#include "illum/framework/method.h"
#include "illum/run/method_help.h"
#include "illum/run/render_job.h"
#include "render_util.h"
#include "test_util.h"

namespace vgi {

using test::render;

using test::meanColor;
using test::writeSkyTriangleScene;

TEST(NearField, EscapingRaysReadTheEnvironmentExactly) {
  const glm::vec3 expect = glm::vec3(0.8f, 0.1f, 0.1f) * glm::vec3(0.5f, 0.25f, 1.0f);
  for (const char* res : {"1", "0.25"}) {
    RenderOutput nf = render(writeSkyTriangleScene("nearfield_sky_triangle"), "nearfield",
                             {std::string("resolution=") + res}, 32, 1, {"indirect"});
    const Image& ind = nf.result.aovs.at("indirect");
    // The camera looks at the triangle's interior: the centre 8×8 pixels see only it.
    for (int y = 12; y < 20; ++y)
      for (int x = 12; x < 20; ++x)
        for (int k = 0; k < 3; ++k) {
          EXPECT_NEAR(ind.at(x, y)[k], expect[k], 1e-6f) << res << " at " << x << "," << y;
          EXPECT_NEAR(nf.result.image.at(x, y)[k], expect[k], 1e-6f) << res;
        }
  }
  RenderOutput off = render(writeSkyTriangleScene("nearfield_sky_triangle"), "nearfield", {"env=false"}, 32,
                            1, {"indirect"});
  EXPECT_EQ(off.result.aovs.at("indirect").at(16, 16), glm::vec3(0.0f));
}

// Cornell box, full resolution, no interleaving or blur, enough frames to
// converge: the combined image and the indirect light against the exact
// integral. Thresholds sit above the values measured at this size (README of
// the bench: scenes/experiments/nearfield-resolution.json) with room for the references' noise.
TEST(NearField, CornellBoxMatchesTheExactNearFieldIntegral) {
  // A short radius (0.1 × the diagonal, the default's fifth): the harder case,
  // where position errors of a voxel matter most.
  const std::string radius = "radius=0.0960740447";
  RenderOutput nf =
      render("builtin:cornell", "nearfield",
             {"voxels=128", "resolution=1", "interleave=1", "blur=false", radius}, 64, 32, {"indirect"});
  RenderOutput ref =
      render("builtin:cornell", "reference", {"integrator=nearfield", radius}, 64, 512, {"indirect"});
  EXPECT_EQ(nf.stats["gl_errors"], 0);
  EXPECT_FLOAT_EQ(nf.stats["extra"]["radius"].get<float>(), nf.stats["params"]["radius"].get<float>());
  ImageDiff d = compareImages(nf.result.image, ref.result.image);
  EXPECT_LT(d.relMse, 1.2e-4);  // measured 4.5e-5
  // The indirect light: its energy and pixels. Measured at this size: rel.
  // MAE 0.107, energy +1.5 / +0.1 / +0.3 % (r, g, b), against a reference
  // whose own noise is ≈ 0.07 (two seeds differ by 0.096). VGI's voxel-entry
  // back-projection with its offset (backprojection=entry) gives 0.306,
  // +17 / +8 / +18 % and relMSE 1.6e-4: it fails all three bounds.
  glm::dvec3 a = meanColor(nf.result.aovs.at("indirect")), b = meanColor(ref.result.aovs.at("indirect"));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k] / b[k], 1.0, 0.05) << "channel " << k;
  ImageDiff di = compareImages(nf.result.aovs.at("indirect"), ref.result.aovs.at("indirect"));
  EXPECT_LT(di.relMae, 0.15);
  // The red wall bleeds onto the floor near it: the indirect there is reddish.
  const Image& ind = nf.result.aovs.at("indirect");
  glm::vec3 nearRed = ind.at(6, 58);
  EXPECT_GT(nearRed.x, 2.0f * nearRed.y) << nearRed.x << " " << nearRed.y;
}

// The shipped configuration (½ resolution, interleaving, tent blur,
// upsampling) stays close to the full-resolution image. Indirect energy
// measured at this size: −2 / −4 / −4 % (r, g, b); with the old box blur
// and ¼ resolution it was +7 / +8 / +15 %, and +17 / +16 / +26 % while each
// direction set was a wedge of azimuths (SharedSampling.EveryInterleavedSetCovers…).
TEST(NearField, ReducedResolutionStaysCloseToFullResolution) {
  RenderOutput full = render("builtin:cornell", "nearfield", {"resolution=1", "interleave=1", "blur=false"},
                             128, 8, {"indirect"});
  RenderOutput shipped = render("builtin:cornell", "nearfield", {}, 128, 4, {"indirect"});
  EXPECT_LT(compareImages(shipped.result.image, full.result.image).relMse, 0.002);  // measured 0.00046
  glm::dvec3 a = meanColor(shipped.result.aovs.at("indirect")),
             b = meanColor(full.result.aovs.at("indirect"));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k] / b[k], 1.0, 0.08) << "channel " << k;
}

// llvmpipe stops every loop of a shader invocation once 65535 loop
// iterations have run in it in all: one dispatch over 256 rays of a few
// hundred tracer steps lost 85 % of nearfield's indirect light and of
// voxel_ao's open rays. The kit dispatches batches of 16 rays; the result no
// longer depends on the ray count beyond noise.
// Two rooms with a wall half a voxel thick between them (scenes/leak-walls/, the light in the left
// one): the exact near-field integral is exactly 0 in the right room. At half resolution the blur and
// the upsampling average coplanar surfaces across the wall (the rooms' back walls, floors) and the
// wall's front face borrows a room's light; blur_visibility (neighbours only through open voxels)
// and fixup (full-rate gather where no gather pixel lies on the surface), on by default, remove both
// (docs/BENCHMARKS.md, "Remedies": 1.5 % → 0.05 % at 128×64).
TEST(NearField, WallRemediesKeepTheLightOutOfTheDarkRoom) {
  const std::string scene = std::string(VGI_TEST_DATA) + "/../../scenes/leak-walls/wall-0.5v.json";
  const RenderOutput exact = render(scene, "reference", {"integrator=nearfield"}, 64, 16, {"indirect"});
  const RenderOutput plain =
      render(scene, "nearfield", {"blur_visibility=false", "fixup=false"}, 64, 4, {"indirect"});
  const RenderOutput remedied = render(scene, "nearfield", {}, 64, 4, {"indirect"});  // the defaults
  const ImageDiff before = compareImages(plain.result.aovs.at("indirect"), exact.result.aovs.at("indirect"));
  const ImageDiff after =
      compareImages(remedied.result.aovs.at("indirect"), exact.result.aovs.at("indirect"));
  EXPECT_GT(before.darkFraction, 0.3) << "the right room and the wall's face are dark in the exact image";
  EXPECT_GT(before.leak, 0.005) << "without the remedies light crosses the wall";
  EXPECT_LT(after.leak, 0.003) << "with them it stays in its room";
  EXPECT_LT(after.relMse, before.relMse) << "and the image is closer to the exact one";
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(after.energyRgb[c], 1.0, 0.05) << c;
  EXPECT_GT(remedied.stats["timings_ms"].value("fixup", 0.0), 0.0) << "the fix-up ran";
}

TEST(NearField, ManyRaysPerPixelAreAllTraced) {
  for (const char* method : {"nearfield", "voxel_ao"}) {
    const bool ao = std::string(method) == "voxel_ao";
    const std::vector<std::string> aovs =
        ao ? std::vector<std::string>{} : std::vector<std::string>{"indirect"};
    RenderOutput few = render("builtin:cornell", method, {"rays=16", "tracer=dda"}, 32, 4, aovs);
    RenderOutput many = render("builtin:cornell", method, {"rays=256", "tracer=dda"}, 32, 1, aovs);
    const double a = test::meanOf(ao ? many.result.image : many.result.aovs.at("indirect"), 1);
    const double b = test::meanOf(ao ? few.result.image : few.result.aovs.at("indirect"), 1);
    EXPECT_NEAR(a / b, 1.0, 0.05) << method;
  }
}

// hierarchical == dda on every ray (tests/traverse), so the images are equal
// bit for bit when each ray is traced once. With passthrough (the default),
// rays resumed past voxels near the receiver's plane differ on a few pixels
// between the two programs (relMSE 4.9e-5 at 32²), though both tracers agree
// on such resumed rays in tests/traverse (RayTracers.ResumedPast…): not yet
// explained, so it is bounded here rather than hidden.
TEST(NearField, TracerIsAParameterAndExactTracersAgreeBitForBit) {
  RenderOutput h =
      render("builtin:cornell", "nearfield", {"tracer=hierarchical", "passthrough=false"}, 32, 1);
  RenderOutput d = render("builtin:cornell", "nearfield", {"tracer=dda", "passthrough=false"}, 32, 1);
  RenderOutput m = render("builtin:cornell", "nearfield", {"tracer=march"}, 32, 1);
  EXPECT_EQ(h.result.image.pixels, d.result.image.pixels);
  RenderOutput hp = render("builtin:cornell", "nearfield", {"tracer=hierarchical"}, 32, 1);
  RenderOutput dp = render("builtin:cornell", "nearfield", {"tracer=dda"}, 32, 1);
  EXPECT_LT(compareImages(hp.result.image, dp.result.image).relMse, 2e-4);
  EXPECT_EQ(m.stats["params"]["tracer"], "march");
  EXPECT_LT(compareImages(m.result.image, hp.result.image).relMse, 0.01);
}

namespace {
// The Cornell box with a 0.1-wide cube gliding just above the floor from left
// to right (time 0 → 1), written as an OBJ + scene JSON. The floor around it
// gathers its occlusion, so stale voxels show.
std::string movingCubeScene() {
  const std::string obj = testing::TempDir() + "/moving_cube.obj",
                    json = testing::TempDir() + "/moving_cube.json";
  std::ofstream o(obj);
  for (int i = 0; i < 8; ++i)
    o << "v " << (i & 1 ? 0.05 : -0.05) << " " << (i & 2 ? 0.05 : -0.05) << " " << (i & 4 ? 0.05 : -0.05)
      << "\n";
  o << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  o.close();
  std::ofstream(json) << R"({ "meshes": [ {"path": "builtin:cornell"},
      {"path": ")" << obj
                      << R"(", "dynamic": true, "keyframes": [
        {"time": 0, "translate": [0.12, 0.07, 0.2]}, {"time": 1, "translate": [0.44, 0.07, 0.2]} ] } ] })";
  return json;
}

struct Animation {
  std::vector<Image> images;
  RenderOutput last;
};
// 32², one sample, full-resolution indirect: small, and every voxel counts.
RenderOptions smallNearField(const std::string& scene) {
  RenderOptions o;
  o.scene = scene;
  o.method = "nearfield";
  o.set = {"resolution=1", "interleave=1"};
  o.width = o.height = 32;
  o.spp = 1;
  o.progress = false;
  return o;
}

// Frames without the temporal filter (each frame its own samples): what these tests hold is that the
// resources follow the animation, frame by frame (the filter has its tests: temporal_test.cpp).
Animation animate(const std::string& scene, int frames, float step) {
  RenderOptions o = smallNearField(scene);
  o.set.push_back("temporal=false");
  o.frames = frames;
  o.timeStep = step;
  Animation a;
  a.last = runRender(o, [&](int frame, const RenderOutput& out) {
    EXPECT_EQ(frame, int(a.images.size()));
    a.images.push_back(out.result.image);
  });
  return a;
}
}  // namespace

// A light on a path (scenes' "keyframes" of a light): every frame of `--frames` equals a still at its
// time, and a still at a time equals the scene with the light placed there (--light): the light maps,
// the radiance and the exact side all follow it; the grid is kept (lights only relight).
TEST(NearField, AMovingLightsFramesEqualStillsWithTheLightPlaced) {
  const std::string scene = testing::TempDir() + "/moving_light.json";
  std::ofstream(scene) << R"({"meshes": [{"path": "builtin:cornell"}], "lights": [{"type": "point",
      "position": [0.3, 0.4, 0.3], "intensity": 0.05, "keyframes": [
        {"time": 0, "position": [0.12, 0.45, 0.2]}, {"time": 1, "position": [0.42, 0.45, 0.38]}]}]})";
  Animation a = animate(scene, 2, 1.0f);
  ASSERT_EQ(a.images.size(), 2u);
  EXPECT_GT(compareImages(a.images[0], a.images[1]).relMse, 0.01) << "the light moved";
  for (int f = 0; f < 2; ++f) {
    RenderOptions o = smallNearField(scene);
    o.time = float(f);
    EXPECT_EQ(runRender(o).result.image.pixels, a.images[size_t(f)].pixels) << "frame " << f;
    RenderOptions placed = smallNearField(scene);
    placed.lightPositions = {{0, f == 0 ? glm::vec3(0.12f, 0.45f, 0.2f) : glm::vec3(0.42f, 0.45f, 0.38f)}};
    EXPECT_EQ(runRender(placed).result.image.pixels, a.images[size_t(f)].pixels) << "frame " << f;
  }
  // The exact reference follows the same path.
  RenderOptions ref = smallNearField(scene);
  ref.method = "reference";
  ref.set = {"integrator=direct"};
  ref.frames = 2;
  ref.timeStep = 1.0f;
  std::vector<Image> refs;
  runRender(ref, [&](int, const RenderOutput& out) { refs.push_back(out.result.image); });
  ASSERT_EQ(refs.size(), 2u);
  ref.frames = 1;
  ref.time = 1.0f;
  EXPECT_EQ(runRender(ref).result.image.pixels, refs[1].pixels);
  EXPECT_GT(compareImages(refs[0], refs[1]).relMse, 0.01);
}

// `--frames`: static meshes are voxelized once and the cube re-inserted per
// frame; every frame must equal a still rendered from scratch at its time
// (the kept static grid, the rebuilt pyramid and RSMs are not stale).
TEST(NearField, AnimationFramesEqualStillsAtTheirTimes) {
  const std::string scene = movingCubeScene();
  Animation a = animate(scene, 3, 0.5f);
  ASSERT_EQ(a.images.size(), 3u);
  const nlohmann::json& frames = a.last.stats["frames"];
  ASSERT_EQ(frames.size(), 3u);
  for (int f = 0; f < 3; ++f) {
    RenderOptions o = smallNearField(scene);
    o.time = 0.5f * float(f);
    RenderOutput still = runRender(o);
    EXPECT_EQ(a.images[size_t(f)].pixels, still.result.image.pixels) << "frame " << f;
    EXPECT_FLOAT_EQ(frames[size_t(f)]["time"].get<float>(), 0.5f * float(f));
    EXPECT_TRUE(frames[size_t(f)]["extra"]["grid"]["rebuilt_this_frame"].get<bool>());
    EXPECT_EQ(frames[size_t(f)]["extra"]["grid"]["stats"]["dynamic_meshes"], 1);
  }
  // The cube moved: the frames differ, and only frame 0 built the atlases.
  EXPECT_GT(compareImages(a.images[0], a.images[2]).relMae, 0.01);
  EXPECT_TRUE(frames[0]["timings_ms"].contains("atlas_build"));
  EXPECT_FALSE(frames[1]["timings_ms"].contains("atlas_build"));
  // Frames after the first draw again only the RSM faces that see the cube (on the floor: the light's
  // downward face), and are the stills above all the same.
  const nlohmann::json maps0 = frames[0]["extra"]["light_maps"], maps1 = frames[1]["extra"]["light_maps"];
  EXPECT_EQ(maps0["faces_redrawn"], maps0["faces_drawn"]) << maps0.dump();
  EXPECT_GE(maps1["faces_redrawn"].get<int>(), 1) << maps1.dump();
  EXPECT_LT(maps1["faces_redrawn"].get<int>(), maps1["faces_drawn"].get<int>()) << maps1.dump();
  // … each within the rectangle the cube's bounds (before and after) project to; frame 0 whole.
  EXPECT_EQ(maps1["faces_scissored"], maps1["faces_redrawn"]) << maps1.dump();
  EXPECT_EQ(maps0["faces_scissored"], 0) << maps0.dump();
  EXPECT_EQ(a.last.stats["frames_completed"], 3);
  EXPECT_EQ(a.last.stats["gl_errors"], 0);
}

// A static scene animates to the same image every frame, built once.
TEST(NearField, StaticSceneIsBuiltOnceAcrossFrames) {
  Animation a = animate("builtin:cornell", 2, 1.0f);
  ASSERT_EQ(a.images.size(), 2u);
  EXPECT_EQ(a.images[0].pixels, a.images[1].pixels);
  EXPECT_FALSE(a.last.stats["frames"][1]["extra"]["grid"]["rebuilt_this_frame"].get<bool>());
  EXPECT_FALSE(a.last.stats["frames"][1]["timings_ms"].contains("rsm"));
  EXPECT_NE(a.last.stats["warnings"].dump().find("no dynamic meshes"), std::string::npos);
}

TEST(Modules, HelpListsParametersNeedsAndOutputs) {
  std::string help = describeMethod("nearfield", "builtin:cornell");
  for (const char* s : {"rays", "radius", "resolution", "tracer", "env", "interleave", "blur", "offset",
                        "voxels", "shadow_res", "needs: gbuffer, gpu_scene, rsm, binary_grid, or_mip_pyramid",
                        "outputs: image, direct, indirect"})
    EXPECT_NE(help.find(s), std::string::npos) << s << " not in:\n" << help;
  // vct's radiance volume is a resource kind: its needs name it (radiance=atlas: the value grids are the volume).
  help = describeMethod("vct", "builtin:cornell");
  EXPECT_NE(help.find("needs: gbuffer, gpu_scene, light_maps, binary_grid, or_mip_pyramid, cone_volume"),
            std::string::npos)
      << help;
}

TEST(Modules, BadParametersAndOutputsAreErrors) {
  test::expectError([] { render("builtin:cornell", "nearfield", {"resolution=0.3"}, 8, 1); },
                    {"resolution", "0.3", "1, 0.5, 0.25"});
  test::expectError([] { render("builtin:cornell", "nearfield", {"tracer=embree"}, 8, 1); },
                    {"tracer", "embree"});
  test::expectError([] { render("builtin:cornell", "nearfield", {"voxels=100"}, 8, 1); }, {"voxels", "100"});
  test::expectError([] { render("builtin:cornell", "nearfield", {"rays=0"}, 8, 1); }, {"rays", "0"});
  test::expectError([] { render("builtin:cornell", "nearfield", {"voxelizer=bogus"}, 8, 1); },
                    {"voxelizer", "bogus", "atlas"});
  test::expectError([] { render("builtin:cornell", "nearfield", {"raidus=1"}, 8, 1); }, {"raidus"});
  test::expectError([] { render("builtin:cornell", "nearfield", {}, 8, 1, {"glow"}); },
                    {"--aov", "glow", "direct, indirect"});
  test::expectError([] { render("builtin:cornell", "direct", {}, 8, 1, {"indirect"}); },
                    {"indirect", "none"});
  test::expectError(
      [] {
        render("builtin:cornell", "reference", {"integrator=ao", "visibility=voxels"}, 8, 1);
      },
      {"visibility", "integrator=ao"});
  test::expectError([] { render("builtin:cornell", "voxelpath", {"maxdepth=0"}, 8, 1); }, {"maxdepth", "0"});
  test::expectError([] { render("builtin:cornell", "voxelpath", {"hitpoint=surface"}, 8, 1); },
                    {"hitpoint", "surface", "entry"});
  test::expectError([] { render("builtin:cornell", "voxelpath", {"voxelizer=slicemap"}, 8, 1); },
                    {"voxelizer", "slicemap", "atlas"});
  test::expectError([] { render("builtin:cornell", "voxelpath", {"clamp=nan"}, 8, 1); }, {"clamp", "nan"});
  test::expectError([] { render("builtin:cornell", "vpl", {"vpls=-1"}, 8, 1); }, {"vpls", "-1"});
  test::expectError([] { render("builtin:cornell", "vpl", {"bounces=0"}, 8, 1); }, {"bounces", "0"});
  test::expectError([] { render("builtin:cornell", "vpl", {"clamp=inf"}, 8, 1); }, {"clamp", "inf"});
  test::expectError(
      [] {
        render("builtin:cornell", "vpl", {"visibility=exact", "fixup=true"}, 8, 1);
      },
      {"fixup", "visibility=voxels", "exact"});
  test::expectError(
      [] {
        render("builtin:cornell", "vpl", {"vpls=1048576", "bounces=8"}, 8, 1);
      },
      {"vpls", "1048576", "bounces", "MiB"});
  test::expectError([] { render("builtin:cornell", "vpl", {"visibility=shadowmaps"}, 8, 1); },
                    {"visibility", "shadowmaps", "voxels"});
  // Bounce VPLs read the value grids, which only the atlas voxelizer makes; one bounce takes any.
  test::expectError([] { render("builtin:cornell", "vpl", {"voxelizer=slicemap"}, 8, 1); },
                    {"voxelizer", "slicemap", "atlas"});
  EXPECT_NO_THROW(
      render("builtin:cornell", "vpl", {"voxelizer=slicemap", "bounces=1", "shadow_res=64"}, 8, 1));
}

}  // namespace vgi
