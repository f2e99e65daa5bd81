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

// The trimmed relMSE drops the top 0.1 % of the pixels' errors: two fireflies among 2000 pixels
// of a uniform 10 % error are dropped; below 1000 pixels nothing is.
TEST(ImageMetrics, TrimmedRelMseDropsTheTopTenthOfAPercentOfPixels) {
  Image a(40, 50), b(40, 50);
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    b.pixels[i] = glm::vec3(1.0f);
    a.pixels[i] = glm::vec3(1.1f);
  }
  a.pixels[7] = a.pixels[1500] = glm::vec3(50.0f);
  const ImageDiff d = compareImages(a, b);
  const double q = 0.01 / 1.01;  // (0.1)² / (1 + ε)
  EXPECT_NEAR(d.relMseTrimmed, q, 1e-6);
  EXPECT_GT(d.relMse, 1.0);  // the fireflies decide the untrimmed mean
  Image small(20, 20), ref(20, 20);
  small.pixels[3] = glm::vec3(9.0f);
  const ImageDiff s = compareImages(small, ref);
  EXPECT_DOUBLE_EQ(s.relMseTrimmed, s.relMse);
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
  DiffOptions zero;
  zero.epsilon = 0.0;
  test::expectError([&] { compareImages(a, b, "a", "b", zero); }, {"epsilon"});
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

// The leak (core/image_metrics.h): a's light where the reference is dark over the reference's light
// elsewhere. Two rooms side by side: the left lit (1), the right dark (0).
TEST(ImageMetrics, LeakIsTheLightWhereTheReferenceIsDark) {
  Image b(8, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) b.at(x, y) = glm::vec3(x < 4 ? 1.0f : 0.0f);
  // The exact counterpart against itself: exactly 0, half the image dark.
  ImageDiff self = compareImages(b, b);
  EXPECT_EQ(self.leak, 0.0);
  EXPECT_EQ(self.darkFraction, 0.5);
  // 5 % of the lit room's light appears in the dark room (and the lit room's level is unchanged).
  Image a = b;
  for (int y = 0; y < 4; ++y)
    for (int x = 4; x < 8; ++x) a.at(x, y) = glm::vec3(0.05f);
  EXPECT_NEAR(compareImages(a, b).leak, 0.05, 1e-7);
  // A dim, not dark, right room (noise of a reference): dark only within the tolerance.
  Image dim = b;
  for (int y = 0; y < 4; ++y)
    for (int x = 4; x < 8; ++x) dim.at(x, y) = glm::vec3(0.001f);
  EXPECT_EQ(compareImages(a, dim).darkFraction, 0.0);
  EXPECT_EQ(compareImages(a, dim).leak, 0.0);
  DiffOptions tolerant;
  tolerant.darkTolerance = 0.01;  // dark: r+g+b <= 0.01 x its mean (1.5015)
  ImageDiff t = compareImages(a, dim, "a", "dim", tolerant);
  EXPECT_EQ(t.darkFraction, 0.5);
  EXPECT_NEAR(t.leak, 0.05 / 1.0, 1e-6);
  test::expectError(
      [&] {
        DiffOptions o;
        o.darkTolerance = -1.0;
        compareImages(a, b, "a", "b", o);
      },
      {"dark tolerance", "-1"});
  // Nothing dark: the leak is 0 and says so through its dark share.
  EXPECT_EQ(compareImages(b, a).darkFraction, 0.0);
}

// The temporal error: the method's frame-to-frame change against the exact one's.
TEST(ImageMetrics, TemporalErrorComparesFrameToFrameChanges) {
  Image grey(4, 4), ramp(4, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) grey.at(x, y) = glm::vec3(0.5f), ramp.at(x, y) = glm::vec3(0.25f * x);
  // A constant image against a constant image: zero, whatever the static error (grey is not ramp).
  SequenceDiff still = compareSequences({grey, grey, grey}, {ramp, ramp, ramp});
  EXPECT_EQ(still.temporalError, 0.0);
  EXPECT_EQ(still.changeA, 0.0);
  EXPECT_EQ(still.frames, 3);
  // Both brighten alike by 0.1 per frame: zero; the method flickers (+0.1, -0.1) where the exact stays:
  // |Δa − Δb| = 0.1 per channel per frame, over the exact level of frames 1 and 2.
  auto plus = [](Image im, float v) {
    for (auto& p : im.pixels) p += glm::vec3(v);
    return im;
  };
  EXPECT_NEAR(
      compareSequences({ramp, plus(ramp, 0.1f), plus(ramp, 0.2f)}, {grey, plus(grey, 0.1f), plus(grey, 0.2f)})
          .temporalError,
      0.0, 1e-7);
  SequenceDiff flicker = compareSequences({grey, plus(grey, 0.1f), grey}, {grey, grey, grey});
  EXPECT_NEAR(flicker.temporalError, 0.1 * 2 / (0.5 * 2), 1e-6);
  EXPECT_NEAR(flicker.changeA, 0.2 / (0.6 + 0.5), 1e-6);
  EXPECT_EQ(flicker.changeB, 0.0);
  // Doubling the method's change doubles the error.
  SequenceDiff twice = compareSequences({grey, plus(grey, 0.2f), grey}, {grey, grey, grey});
  EXPECT_NEAR(twice.temporalError, 2 * flicker.temporalError, 1e-6);
  test::expectError([&] { compareSequences({grey}, {grey}, "a", "b"); }, {"at least 2 frames"});
  test::expectError([&] { compareSequences({grey, grey}, {grey, Image(4, 5)}, "a", "b"); }, {"b frame 1"});
}

}  // namespace vgi
