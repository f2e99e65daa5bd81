// FLIP (core/flip.h) against the values published for it and the papers' constants: the uniform
// grey pair OpenImageIO's test suite publishes for its own implementation of the papers (LDR-FLIP
// 0.9514, HDR-FLIP 0.2045 over 2 exposures at 4.41 stops), identical images, the viewing
// condition's filter radii, the colour normaliser, the tone curve's 0.85 point, the feature
// detectors on an edge and a point, and the pooling.
#include "core/flip.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace vgi {

namespace {
Image uniform(int w, int h, float v) {
  Image img(w, h);
  for (auto& p : img.pixels) p = glm::vec3(v);
  return img;
}
}  // namespace

// The published pair: 64×64 grey 0.1 and 0.9 stored as half floats, 0.1 the reference.
TEST(Flip, ReproducesThePublishedUniformGreyPair) {
  const Image ref = uniform(64, 64, 0.099975586f), test = uniform(64, 64, 0.89990234f);
  const FlipResult ldr = ldrFlip(test, ref);
  EXPECT_NEAR(ldr.pooled.mean, 0.9514, 5e-5);
  EXPECT_NEAR(ldr.pooled.max, 0.9514, 5e-5);
  EXPECT_NEAR(ldr.pooled.median, 0.9514, 5e-5);
  const FlipResult hdr = hdrFlip(test, ref);
  EXPECT_NEAR(hdr.pooled.mean, 0.2045, 5e-5);
  EXPECT_EQ(hdr.exposures, 2);
  EXPECT_NEAR(hdr.startExposure, 4.41, 5e-3);
  EXPECT_NEAR(hdr.stopExposure, 4.41, 5e-3);
  std::printf("LDR-FLIP %.6f, HDR-FLIP %.6f (exposures %.4f to %.4f)\n", ldr.pooled.mean, hdr.pooled.mean,
              hdr.startExposure, hdr.stopExposure);
}

TEST(Flip, IdenticalImagesAreZero) {
  Image img(48, 32);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 4.0f);
  for (auto& p : img.pixels) p = glm::vec3(u(rng), u(rng), u(rng));
  EXPECT_EQ(ldrFlip(img, img).pooled.max, 0.0);
  EXPECT_EQ(hdrFlip(img, img).pooled.max, 0.0);
}

// 0.7 m from a 0.7 m display of 3840 pixels: 67.02 pixels per degree, the contrast-sensitivity
// filters 10 pixels wide each way (3 standard deviations of the widest, Cz's b = 0.04), the feature
// detectors σ = ½ · 0.082° · ppd ≈ 2.75 pixels, 9 pixels each way.
TEST(Flip, TheViewingConditionSetsTheFilterRadii) {
  const double ppd = FlipViewing{}.pixelsPerDegree();
  EXPECT_NEAR(ppd, 67.0206, 1e-4);
  EXPECT_EQ(flip_detail::csfRadius(ppd), 10);
  EXPECT_NEAR(flip_detail::featureSigma(ppd), 2.7478, 1e-4);
  EXPECT_EQ(flip_detail::featureRadius(ppd), 9);
  FlipViewing far;
  far.distance = 1.4;  // twice as far: twice the pixels per degree
  EXPECT_NEAR(far.pixelsPerDegree(), 2.0 * ppd, 1e-9);
  EXPECT_EQ(flip_detail::csfRadius(far.pixelsPerDegree()), 19);
}

TEST(Flip, ColourConstantsAreThePapers) {
  EXPECT_NEAR(flip_detail::colourMax(), 41.276, 5e-3);  // HyAB^0.7 of pure green against pure blue
  // The tone curve maps x ≈ 2.119 to 0.85, and saturates.
  const double x = flip_detail::toneMapInputFor085();
  EXPECT_NEAR(x, 2.119, 1e-3);
  EXPECT_NEAR(flip_detail::toneMap(float(x)), 0.85f, 1e-6f);
  EXPECT_EQ(flip_detail::toneMap(1e6f), 1.0f);
  EXPECT_EQ(flip_detail::toneMap(0.0f), 0.0f);
  // White is L = 100 with no chroma; black L = 0.
  const float white[3] = {1, 1, 1}, black[3] = {0, 0, 0};
  float lab[3];
  flip_detail::huntLab(white, lab);
  EXPECT_NEAR(lab[0], 100.0f, 1e-3f);
  EXPECT_NEAR(lab[1], 0.0f, 1e-3f);
  EXPECT_NEAR(lab[2], 0.0f, 1e-3f);
  flip_detail::huntLab(black, lab);
  EXPECT_NEAR(lab[0], 0.0f, 1e-4f);
}

// The feature detectors: nothing on a uniform image or beyond their radius from an edge; an edge
// of height 1 gives an edge magnitude near 1 at it (the kernel's positive weights sum to 1) and a
// point response beside it; a one-pixel dot gives a point response at it.
TEST(Flip, TheFeatureDetectorsSeeEdgesAndPoints) {
  const int w = 64, h = 16;
  const double ppd = FlipViewing{}.pixelsPerDegree();
  std::vector<float> step(size_t(w) * h), edges, points;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) step[size_t(y) * w + size_t(x)] = x >= w / 2 ? 1.0f : 0.0f;
  flip_detail::features(step, w, h, ppd, edges, points, 1);
  const size_t row = size_t(h / 2) * w;
  EXPECT_GT(edges[row + w / 2], 0.9f);
  EXPECT_LE(edges[row + w / 2], 1.0f + 1e-5f);
  EXPECT_LT(edges[row + w / 2 - 12], 1e-6f);  // 12 > 9 pixels away
  EXPECT_LT(edges[row + w / 2 + 11], 1e-6f);
  EXPECT_GT(points[row + w / 2 + 3], 0.1f);  // beside the edge: the second derivative's lobes
  std::vector<float> flat(size_t(w) * h, 0.5f);
  flip_detail::features(flat, w, h, ppd, edges, points, 1);
  for (size_t i = 0; i < flat.size(); ++i) {
    EXPECT_LT(edges[i], 1e-6f);
    EXPECT_LT(points[i], 1e-6f);
  }
  std::vector<float> dot(size_t(w) * h, 0.0f);
  dot[row + 20] = 1.0f;
  flip_detail::features(dot, w, h, ppd, edges, points, 1);
  EXPECT_GT(points[row + 20], 0.0f);
  // FLIP of an edge moved by two pixels: the feature term raises the colour error there.
  Image a(w, h), b(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      a.at(x, y) = glm::vec3(x >= w / 2 ? 0.8f : 0.2f);
      b.at(x, y) = glm::vec3(x >= w / 2 + 2 ? 0.8f : 0.2f);
    }
  const FlipResult f = ldrFlip(a, b);
  EXPECT_GT(f.pooled.max, 0.5);
  EXPECT_LT(f.map[row + 5], 1e-6f) << "far from the edges the images agree";
  EXPECT_GE(f.pooled.maxX, w / 2 - 2);
  EXPECT_LE(f.pooled.maxX, w / 2 + 3);
}

// The weighted median and quartiles: where the running sum of the sorted values passes ½, ¼, ¾.
TEST(Flip, PoolingIsTheWeightedPercentiles) {
  const FlipPooled p = poolFlip({0.3f, 0.1f, 0.4f, 0.2f}, 2);
  EXPECT_NEAR(p.mean, 0.25, 1e-7);
  EXPECT_FLOAT_EQ(float(p.q1), 0.2f);  // running sums 0.1, 0.3, 0.6, 1.0
  EXPECT_FLOAT_EQ(float(p.median), 0.3f);
  EXPECT_FLOAT_EQ(float(p.q3), 0.4f);
  EXPECT_FLOAT_EQ(float(p.max), 0.4f);
  EXPECT_EQ(p.maxX, 0);
  EXPECT_EQ(p.maxY, 1);
  const FlipPooled zero = poolFlip({0.0f, 0.0f}, 2);
  EXPECT_EQ(zero.median, 0.0);
}

// A reference with a black majority takes the median of its lit pixels; an all-black one does not
// fail (one exposure of 0, twice).
TEST(Flip, HdrExposuresOfDarkReferences) {
  Image ref = uniform(8, 8, 0.0f), test = uniform(8, 8, 0.5f);
  const FlipResult black = hdrFlip(test, ref);
  EXPECT_EQ(black.exposures, 2);
  EXPECT_EQ(black.startExposure, 0.0);
  EXPECT_GT(black.pooled.mean, 0.0);
  for (int i = 0; i < 8; ++i) ref.pixels[size_t(i)] = glm::vec3(1.0f);  // 8 of 64 lit
  const FlipResult dark = hdrFlip(test, ref);
  EXPECT_NEAR(dark.startExposure, dark.stopExposure, 1e-9);  // the lit pixels' median is their max
  EXPECT_TRUE(std::isfinite(dark.pooled.mean));
}

TEST(Flip, SizesMustAgree) {
  EXPECT_THROW(ldrFlip(uniform(4, 4, 0.1f), uniform(4, 5, 0.1f)), std::exception);
  EXPECT_THROW(hdrFlip(Image(), Image()), std::exception);
}

}  // namespace vgi
