#include "core/image.h"

#include "core/image_metrics.h"
#include "test_util.h"

namespace vgi {

TEST(Image, ExrRoundTripIsExactAndPngIsWritten) {
  Image a(7, 5);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x) a.at(x, y) = {x * 0.25f, y * 10.5f, 1e-4f * float(x + y)};
  std::string exr = testing::TempDir() + "/rt.exr", png = testing::TempDir() + "/rt.png";
  writeImage(a, exr);
  writeImage(a, png);
  Image b = readImage(exr);
  ASSERT_EQ(b.width, 7);
  ASSERT_EQ(b.height, 5);
  for (size_t i = 0; i < a.pixels.size(); ++i) EXPECT_EQ(a.pixels[i], b.pixels[i]);
  Image c = readImage(png);
  EXPECT_EQ(c.width, 7);
  test::expectError([&] { writeImage(a, "/no/such/folder/x.exr"); }, {"/no/such/folder"});
}

TEST(ImageMetrics, IdenticalImagesHaveNoErrorAndSsimOne) {
  Image a(16, 16);
  for (size_t i = 0; i < a.pixels.size(); ++i) a.pixels[i] = glm::vec3(float(i % 7) * 0.1f);
  ImageDiff d = compareImages(a, a);
  EXPECT_EQ(d.rmse, 0.0);
  EXPECT_EQ(d.relMse, 0.0);
  EXPECT_EQ(d.mae, 0.0);
  EXPECT_NEAR(d.ssim, 1.0, 1e-12);
}

TEST(ImageMetrics, HandComputedValues) {
  Image a(1, 1), b(1, 1);
  a.pixels[0] = glm::vec3(1.5f, 1.0f, 1.0f);
  b.pixels[0] = glm::vec3(1.0f, 1.0f, 0.0f);
  ImageDiff d = compareImages(a, b);
  EXPECT_NEAR(d.mae, (0.5 + 0 + 1) / 3.0, 1e-7);
  EXPECT_NEAR(d.rmse, std::sqrt((0.25 + 0 + 1) / 3.0), 1e-7);
  EXPECT_NEAR(d.relMse, (0.25 / 1.01 + 0 + 1 / 0.01) / 3.0, 1e-5);
}

// A dim image (an indirect channel): the fixed ε hides a 50 % error, the
// relative one does not; per-channel rel. MAE and energy are hand-computed.
TEST(ImageMetrics, RelativeEpsilonPerChannelErrorsAndSignedDifference) {
  Image a(2, 1), b(2, 1);
  b.pixels = {glm::vec3(0.002f, 0.004f, 0.0f), glm::vec3(0.002f, 0.0f, 0.001f)};
  a.pixels = {glm::vec3(0.003f, 0.004f, 0.0f), glm::vec3(0.003f, 0.0f, 0.0f)};
  ImageDiff fixed = compareImages(a, b);
  EXPECT_LT(fixed.relMse, 1e-4);
  DiffOptions rel;
  rel.relativeEpsilon = 0.1;
  ImageDiff d = compareImages(a, b, "a", "b", rel);
  const double mean = (0.002 + 0.004 + 0.002 + 0.001) / 6.0;
  EXPECT_NEAR(d.epsilon, 0.01 * mean * mean, 1e-12);
  EXPECT_GT(d.relMse, 0.1);
  EXPECT_NEAR(d.relMaeRgb[0], 0.002 / 0.004, 1e-5);  // red: +0.001 twice over 0.004
  EXPECT_NEAR(d.relMaeRgb[1], 0.0, 1e-7);
  EXPECT_NEAR(d.relMaeRgb[2], 1.0, 1e-5);  // blue: all of it missing
  EXPECT_NEAR(d.energyRgb[0], 1.5, 1e-5);
  EXPECT_NEAR(d.energyRgb[2], 0.0, 1e-7);
  Image e = signedDifference(a, b);
  EXPECT_NEAR(e.pixels[1].z, -0.001f, 1e-9f);
  test::expectError([&] { compareImages(a, b, "a", "b", DiffOptions{0.0, 0.0}); }, {"epsilon"});
}

TEST(ImageMetrics, RefusesDifferentSizesAndNaN) {
  Image a(4, 4), b(4, 5);
  test::expectError([&] { compareImages(a, b, "a.exr", "b.exr"); },
                    {"different sizes", "a.exr is 4x4", "b.exr is 4x5"});
  Image c(4, 4);
  c.pixels[5].y = std::nanf("");
  test::expectError([&] { compareImages(c, a, "c.exr", "a.exr"); }, {"c.exr", "non-finite", "(1, 1)"});
}

TEST(ImageMetrics, SsimDropsWithNoise) {
  Image a(32, 32), b(32, 32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      a.at(x, y) = glm::vec3(float(x) / 32.0f);
      b.at(x, y) = a.at(x, y) + glm::vec3(((x * 7 + y * 13) % 5 - 2) * 0.05f);
    }
  ImageDiff d = compareImages(b, a);
  EXPECT_LT(d.ssim, 0.95);
  EXPECT_GT(d.ssim, 0.0);
}

}  // namespace vgi
