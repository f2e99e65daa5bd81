// The shared kernels (shaders/shared/) on their hard cases: bases near ±z,
// sampling at the pole and horizon, hash-to-float range, light cones, BRDF
// normalisation.
#include "shaders/shared/sampling.glsl"

#include <algorithm>
#include <random>

#include "shaders/shared/brdf.glsl"
#include "shaders/shared/lights.glsl"
#include "test_util.h"

namespace vgi {
using namespace vgi::shared;

namespace {
void expectOrthonormal(const Basis& f) {
  EXPECT_NEAR(glm::length(f.t), 1.0f, 1e-5f);
  EXPECT_NEAR(glm::length(f.b), 1.0f, 1e-5f);
  EXPECT_NEAR(dot(f.t, f.b), 0.0f, 1e-5f);
  EXPECT_NEAR(dot(f.t, f.n), 0.0f, 1e-5f);
  EXPECT_NEAR(dot(f.b, f.n), 0.0f, 1e-5f);
  EXPECT_NEAR(dot(cross(f.t, f.b), f.n), 1.0f, 1e-5f);  // right-handed
}
}  // namespace

TEST(SharedSampling, BasisIsOrthonormalNearThePoles) {
  const float tiny = 1e-7f;
  for (glm::vec3 n : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(0, 0, -0.0f) + glm::vec3(0, 0, 1),
                      glm::normalize(glm::vec3(tiny, 0, -1)), glm::normalize(glm::vec3(0, tiny, 1)),
                      glm::normalize(glm::vec3(-tiny, tiny, -1)), glm::vec3(1, 0, 0), glm::vec3(0, -1, 0)})
    expectOrthonormal(makeBasis(n));
  // n.z = −0 takes the +z branch and must still be exact.
  expectOrthonormal(makeBasis(glm::vec3(1, 0, -0.0f)));
  std::mt19937 rng(7);
  std::normal_distribution<float> g;
  for (int i = 0; i < 10000; ++i)
    expectOrthonormal(makeBasis(glm::normalize(glm::vec3(g(rng), g(rng), g(rng)))));
}

TEST(SharedSampling, CosineSamplingAtPoleAndHorizon) {
  const float almostOne = 1.0f - 1.0f / 16777216.0f;  // largest uintToUnitFloat value
  for (glm::vec2 u : {glm::vec2(0, 0), glm::vec2(0, almostOne), glm::vec2(almostOne, 0),
                      glm::vec2(almostOne, almostOne), glm::vec2(0.5f, 0.25f)}) {
    glm::vec3 d = cosineSampleHemisphere(u);
    EXPECT_TRUE(std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z));
    EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
    EXPECT_GE(d.z, 0.0f);
  }
  EXPECT_FLOAT_EQ(cosineSampleHemisphere({0, 0.3f}).z, 1.0f);  // the pole
  // Mean of cos θ under a cosine density is 2/3.
  double sum = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i)
    sum +=
        cosineSampleHemisphere({uintToUnitFloat(pcgHash(2u * i)), uintToUnitFloat(pcgHash(2u * i + 1u))}).z;
  EXPECT_NEAR(sum / n, 2.0 / 3.0, 2e-3);
}

// Interleaved sampling as `nearfield` runs it (k = 4: 16 sets of N = 16):
// each set alone has one sample in each of N strata of u.x and of u.y (so a
// blur window that keeps only some sets stays unbiased in azimuth, u.y), and
// all sets together fill the k²·N strata of u.x and of u.y exactly once.
TEST(SharedSampling, EveryInterleavedSetCoversBothCoordinates) {
  for (uint32_t n : {4u, 16u, 12u}) {
    const uint32_t sets = 16;
    std::vector<int> allX(sets * n, 0), allY(sets * n, 0);
    for (uint32_t s = 0; s < sets; ++s) {
      std::vector<int> x(n, 0), y(n, 0);
      for (uint32_t r = 0; r < n; ++r) {
        glm::vec2 u = shared::interleavedSample(r, s, n, sets);
        ASSERT_TRUE(u.x >= 0.0f && u.x < 1.0f && u.y >= 0.0f && u.y < 1.0f);
        ++x[size_t(u.x * float(n))];
        ++y[size_t(u.y * float(n))];
        ++allX[size_t(u.x * float(sets * n))];
        ++allY[size_t(u.y * float(sets * n))];
      }
      if ((n & (n - 1)) == 0) {  // strata are exact for powers of two (radical inverse)
        EXPECT_EQ(*std::min_element(y.begin(), y.end()), 1) << "set " << s << " of " << n;
      } else {
        EXPECT_LE(*std::max_element(y.begin(), y.end()), 2) << "set " << s << " of " << n;
      }
      EXPECT_EQ(*std::min_element(x.begin(), x.end()), 1) << "set " << s << " of " << n;
    }
    EXPECT_EQ(*std::min_element(allX.begin(), allX.end()), 1);
    if ((n & (n - 1)) == 0) {
      EXPECT_EQ(*std::min_element(allY.begin(), allY.end()), 1);
    }
  }
}

// The per-block rotation nearfield adds (so one frame's interleave pattern
// does not repeat with the block period): in [0, 1)², deterministic, and
// different for neighbouring blocks and frames; over many blocks its offsets
// cover the unit square evenly (no block shares a fixed pattern).
TEST(SharedSampling, BlockRotationsDifferPerBlockAndFrameAndCoverTheSquare) {
  using namespace vgi::shared;
  EXPECT_EQ(blockRotation(3, 5, 0), blockRotation(3, 5, 0));
  EXPECT_NE(blockRotation(3, 5, 0), blockRotation(4, 5, 0));
  EXPECT_NE(blockRotation(3, 5, 0), blockRotation(3, 6, 0));
  EXPECT_NE(blockRotation(3, 5, 0), blockRotation(3, 5, 1));
  int cells[4][4] = {};
  const int n = 64;
  for (uint32_t by = 0; by < n; ++by)
    for (uint32_t bx = 0; bx < n; ++bx) {
      vec2 r = blockRotation(bx, by, 7);
      ASSERT_TRUE(r.x >= 0.0f && r.x < 1.0f && r.y >= 0.0f && r.y < 1.0f);
      ++cells[int(r.y * 4)][int(r.x * 4)];
    }
  // 4096 offsets in 16 cells: 256 expected each (σ ≈ 15.5); ±64 is 4σ. The hash is fixed, so this is
  // deterministic.
  for (auto& row : cells)
    for (int c : row) EXPECT_NEAR(c, 256, 64);
}

TEST(SharedSampling, HashToFloatStaysInUnitInterval) {
  EXPECT_EQ(uintToUnitFloat(0u), 0.0f);
  EXPECT_LT(uintToUnitFloat(0xffffffffu), 1.0f);
  EXPECT_NE(pcgHash(0u), pcgHash(1u));
}

TEST(SharedBrdf, LambertSamplingWeightIsTheAlbedo) {
  BrdfParams m;
  m.albedo = glm::vec3(0.5f, 0.25f, 0.125f);
  m.ks = glm::vec3(0.0f);
  m.exponent = 1.0f;
  glm::vec3 n = glm::normalize(glm::vec3(0.3f, 0.2f, 0.9f));
  glm::vec3 wo = glm::normalize(glm::vec3(-0.2f, 0.4f, 0.8f));
  for (int i = 0; i < 1000; ++i) {
    glm::vec3 u(uintToUnitFloat(pcgHash(3u * i)), uintToUnitFloat(pcgHash(3u * i + 1u)),
                uintToUnitFloat(pcgHash(3u * i + 2u)));
    glm::vec3 wi = sampleBrdf(m, n, wo, u);
    float pdf = brdfPdf(m, n, wo, wi);
    if (dot(wi, n) <= 1e-4f) continue;
    glm::vec3 w = evalBrdf(m, n, wo, wi) * dot(wi, n) / pdf;
    EXPECT_NEAR(w.x, 0.5f, 1e-4f);
    EXPECT_NEAR(w.z, 0.125f, 1e-4f);
  }
}

TEST(SharedBrdf, PhongLobeIsNormalisedAndPdfIntegratesToOne) {
  // At normal incidence the normalised Phong lobe reflects exactly ks of the
  // light: ∫ (e+2)/(2π) cos^e θ cos θ dω = 1. Estimate with uniform directions.
  BrdfParams m;
  m.albedo = glm::vec3(0.0f);
  m.ks = glm::vec3(1.0f);
  m.exponent = 20.0f;
  glm::vec3 n(0, 0, 1);
  const int N = 400000;
  double albedo = 0, pdfIntegral = 0;
  for (int i = 0; i < N; ++i) {
    float u1 = uintToUnitFloat(pcgHash(2u * i + 99u)), u2 = uintToUnitFloat(pcgHash(2u * i + 100u));
    float z = u1, r = std::sqrt(std::max(0.0f, 1 - z * z)), phi = 2 * PI * u2;
    glm::vec3 wi(r * std::cos(phi), r * std::sin(phi), z);  // uniform hemisphere, pdf 1/(2π)
    albedo += evalBrdf(m, n, n, wi).x * z * 2 * PI;
    pdfIntegral += brdfPdf(m, n, n, wi) * 2 * PI;
  }
  EXPECT_NEAR(albedo / N, 1.0, 0.02);
  EXPECT_NEAR(pdfIntegral / N, 1.0, 0.02);
}

TEST(SharedLights, SpotConeAndInverseSquare) {
  PackedLight spot;
  spot.positionType = glm::vec4(0, 2, 0, float(LIGHT_SPOT));
  spot.directionCosCone = glm::vec4(0, -1, 0, std::cos(glm::radians(45.0f)));
  spot.intensityFalloff = glm::vec4(4, 4, 4, 1);
  LightSample below = sampleDeltaLight(spot, glm::vec3(0, 0, 0));
  EXPECT_NEAR(below.radiance.x, 4.0f / 4.0f, 1e-6f);  // I/d², cos 0 = 1
  EXPECT_NEAR(below.dist, 2.0f, 1e-6f);
  LightSample inside = sampleDeltaLight(spot, glm::vec3(1, 0, 0));  // θ = 26.6°
  float d2 = 5.0f, cosT = 2.0f / std::sqrt(5.0f);
  EXPECT_NEAR(inside.radiance.x, 4.0f * cosT / d2, 1e-6f);
  EXPECT_EQ(sampleDeltaLight(spot, glm::vec3(3, 0, 0)).radiance.x, 0.0f);  // θ = 56° > 45°
  // A 90° cone lights the hemisphere below and nothing at or above the horizon.
  spot.directionCosCone.w = std::cos(glm::radians(90.0f));
  EXPECT_EQ(sampleDeltaLight(spot, glm::vec3(1, 2, 0)).radiance.x, 0.0f);
  EXPECT_EQ(sampleDeltaLight(spot, glm::vec3(1, 3, 0)).radiance.x, 0.0f);
  EXPECT_GT(sampleDeltaLight(spot, glm::vec3(100, 1.9f, 0)).radiance.x, 0.0f);
  // The light sitting exactly on the point must not produce NaN or Inf.
  LightSample at = sampleDeltaLight(spot, glm::vec3(0, 2, 0));
  EXPECT_TRUE(std::isfinite(at.radiance.x) && std::isfinite(at.wi.x));
}

}  // namespace vgi
