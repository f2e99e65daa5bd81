// The sample loop's temporal filter (illum/framework/temporal.h): with the camera standing still and
// nothing moving, frames that repeat their samples are the still bit for bit, and frames that continue
// them are the running mean of every sample so far (the history read at its own pixel, not
// resampled); with a moving camera the history follows the surfaces, so the
// last frame of a short pan is closer to the converged image than the same frame alone; stills and
// `temporal=false` are not changed.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/image_metrics.h"
#include "illum/run/render_job.h"
#include "test_util.h"

namespace vgi {
namespace {

RenderOptions smallFrames(const std::string& scene, int frames, int spp, std::vector<std::string> set) {
  RenderOptions o;
  o.scene = scene;
  o.method = "nearfield";
  o.set = std::move(set);
  o.width = o.height = 32;
  o.spp = spp;
  o.frames = frames;
  o.timeStep = 0.25f;
  o.progress = false;
  return o;
}

// Each frame's image, or its output `aov`.
std::vector<Image> frames(const RenderOptions& o, const std::string& aov = "") {
  std::vector<Image> images;
  runRender(o, [&](int, const RenderOutput& out) {
    images.push_back(aov.empty() ? out.result.image : out.result.aovs.at(aov));
  });
  return images;
}

// The share of pixels where a and b differ by more than `rel` of b.
double differingShare(const Image& a, const Image& b, float rel) {
  size_t n = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    const glm::vec3 d = glm::abs(a.pixels[i] - b.pixels[i]);
    const glm::vec3 m = glm::abs(b.pixels[i]) * rel + 1e-6f;
    if (d.x > m.x || d.y > m.y || d.z > m.z) ++n;
  }
  return double(n) / double(a.pixels.size());
}

}  // namespace

// Where nothing changes, frames that repeat their samples (the default) are the still, bit for bit,
// whatever the clipping: nothing flickers.
TEST(Temporal, AStillSceneGivesTheStillEveryFrame) {
  const std::vector<Image> f = frames(smallFrames("builtin:cornell", 3, 2, {}));
  ASSERT_EQ(f.size(), 3u);
  const Image still = runRender(smallFrames("builtin:cornell", 1, 2, {})).result.image;
  for (size_t i = 0; i < f.size(); ++i) EXPECT_EQ(f[i].pixels, still.pixels) << "frame " << i;
}

// Four frames of 2 samples of a still scene, continued, unclipped, with a history long enough: frame
// 3 is the mean of samples 0…7, the image of an 8-sample still (where the jittered G-buffers of two
// frames saw different surfaces — an edge pixel — the history is rejected and the pixel starts again).
TEST(Temporal, ContinuedSamplesAverageEveryFramesSamples) {
  const std::vector<Image> f = frames(smallFrames(
      "builtin:cornell", 4, 2, {"temporal_samples=continue", "temporal_alpha=0.01", "temporal_clamp=0"}));
  ASSERT_EQ(f.size(), 4u);
  RenderOptions still = smallFrames("builtin:cornell", 1, 8, {});
  const Image eight = runRender(still).result.image;
  still.spp = 2;
  const Image two = runRender(still).result.image;
  EXPECT_EQ(f[0].pixels, two.pixels) << "the first frame has no history: a still";
  EXPECT_LT(differingShare(f[3], eight, 1e-4f), 0.08) << "frame 3 is the 8-sample mean but at edges";
  EXPECT_GT(differingShare(f[3], two, 1e-2f), 0.5) << "frame 3 has more than its own samples";
  // Off: every frame is the 2-sample still.
  const std::vector<Image> off = frames(smallFrames("builtin:cornell", 2, 2, {"temporal=false"}));
  ASSERT_EQ(off.size(), 2u);
  EXPECT_EQ(off[1].pixels, two.pixels);
}

// A camera panning across the Cornell box: 6 frames of 1 sample filtered (continued) are nearer the
// converged last view's indirect light than its frame alone (0.66×); the history followed the
// surfaces: read at the same pixel it gives 0.99×, with the motion reversed 1.85× (measured unclipped,
// so that clipping cannot hide a wrong reprojection).
TEST(Temporal, APanningCameraKeepsTheHistoryOfTheSurfaces) {
  const std::string scene = testing::TempDir() + "/temporal_pan.json";
  std::ofstream(scene)
      << R"({"meshes": [{"path": "builtin:cornell"}], "camera": {"position": [0.18, 0.273, -0.8],
      "target": [0.278, 0.273, 0.0], "up": [0, 1, 0], "fov_deg": 40, "keyframes": [
        {"time": 0, "position": [0.18, 0.273, -0.8], "target": [0.278, 0.273, 0.0]},
        {"time": 1.25, "position": [0.38, 0.273, -0.8], "target": [0.278, 0.273, 0.0]}]}})";
  RenderOptions on = smallFrames(scene, 6, 1, {"temporal_samples=continue", "temporal_clamp=0"});
  on.width = on.height = 48;
  on.aovs = {"indirect"};  // the channel the filter is for (the edges' aliasing is the same in both)
  RenderOptions off = on;
  off.set = {"temporal=false"};
  const std::vector<Image> a = frames(on, "indirect"), b = frames(off, "indirect");
  ASSERT_EQ(a.size(), 6u);
  ASSERT_EQ(b.size(), 6u);
  RenderOptions converged = on;
  converged.frames = 1;
  converged.time = 1.25f;
  converged.spp = 64;
  const Image truth = runRender(converged).result.aovs.at("indirect");
  const double filtered = compareImages(a[5], truth).relMse, alone = compareImages(b[5], truth).relMse;
  EXPECT_LT(filtered, 0.8 * alone) << "filtered " << filtered << ", the frame alone " << alone;
  EXPECT_GT(compareImages(b[0], b[5]).relMae, 0.05) << "the camera moved";
}

TEST(Temporal, BadSettingsAreRefused) {
  test::expectError([] { runRender(smallFrames("builtin:cornell", 2, 1, {"temporal_alpha=0"})); },
                    {"temporal_alpha", "0"});
  test::expectError([] { runRender(smallFrames("builtin:cornell", 2, 1, {"temporal_clamp=-1"})); },
                    {"temporal_clamp", "-1"});
  test::expectError([] { runRender(smallFrames("builtin:cornell", 2, 1, {"temporal_samples=all"})); },
                    {"temporal_samples", "all", "repeat", "continue"});
}

}  // namespace vgi
