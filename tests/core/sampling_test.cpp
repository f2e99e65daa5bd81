// The shared kernels (shaders/shared/) on their hard cases: bases near ±z,
// sampling at the pole and horizon, hash-to-float range, light cones, BRDF
// normalisation.
#include "shaders/shared/sampling.glsl"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "core/gl_context.h"
#include "core/shader_library.h"
#include "shaders/shared/bindings.glsl"
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

// The GPU's numbers are the C++ build's, bit for bit: what a CPU test of a
// sampling routine checks is what the shader draws.
TEST(SharedRng, GlslStreamsAndR2PointsEqualTheCppBuildBitForBit) {
  auto ctx = GlContext::create();
  ShaderLibrary shaders;
  const unsigned prog = shaders.program({"../tests/data/shaders/sampling_probe.comp.glsl"});
  const int n = 4096;
  const uint32_t b = 12345u, c = 0xdeadbeefu, rx = 0x9e3779b9u, ry = 0x7f4a7c15u;
  unsigned buf = 0;
  glCreateBuffers(1, &buf);
  glNamedBufferStorage(buf, GLsizeiptr(n * 6 * sizeof(uint32_t)), nullptr, 0);
  glUseProgram(prog);
  shaders.setUniform(prog, "uB", b);
  shaders.setUniform(prog, "uC", c);
  shaders.setUniform(prog, "uRx", rx);
  shaders.setUniform(prog, "uRy", ry);
  shaders.setUniform(prog, "uCount", n);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_TRACE_HITS, buf);
  glDispatchCompute(n / 64, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<uint32_t> gpu(size_t(n) * 6);
  glGetNamedBufferSubData(buf, 0, GLsizeiptr(gpu.size() * sizeof(uint32_t)), gpu.data());
  glDeleteBuffers(1, &buf);
  auto bits = [](float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
  };
  for (int i = 0; i < n; ++i) {
    uint32_t state = rngSeed(uint32_t(i), b, c);
    for (int k = 0; k < 4; ++k) ASSERT_EQ(gpu[size_t(6 * i + k)], bits(rngNext(state))) << i << " " << k;
    const vec2 r = r2Point(uint32_t(i) * 977u, rx, ry);
    ASSERT_EQ(gpu[size_t(6 * i + 4)], bits(r.x)) << i;
    ASSERT_EQ(gpu[size_t(6 * i + 5)], bits(r.y)) << i;
  }
  EXPECT_EQ(ctx->errorCount(), 0);
}

// Streams of neighbouring pixels and samples, drawn as a path tracer draws
// them: 2¹⁸ streams × 8 numbers, uniform (χ² over 256 bins), uncorrelated
// along a stream and across neighbouring streams, no stream repeating.
TEST(SharedRng, StreamsAreUniformAndIndependent) {
  const int streams = 1 << 18, draws = 8, bins = 256;
  std::vector<double> count(bins, 0.0);
  double sumLag = 0, sumCross = 0, sum = 0, sumSq = 0;
  long pairsLag = 0, pairsCross = 0;
  float previousFirst = 0;
  std::vector<uint32_t> firstStates;
  for (int s = 0; s < streams; ++s) {
    // pixel = s % 512, sample = s / 512, seed 1
    uint32_t state = rngSeed(uint32_t(s % 512), uint32_t(s / 512), 1u);
    firstStates.push_back(state);
    float prev = 0;
    for (int k = 0; k < draws; ++k) {
      const float u = rngNext(state);
      ASSERT_TRUE(u >= 0.0f && u < 1.0f);
      count[size_t(u * bins)] += 1;
      sum += u;
      sumSq += double(u) * u;
      if (k > 0) sumLag += (double(prev) - 0.5) * (double(u) - 0.5), ++pairsLag;
      if (k == 0 && s % 512 > 0) sumCross += (double(previousFirst) - 0.5) * (double(u) - 0.5), ++pairsCross;
      if (k == 0) previousFirst = u;
      prev = u;
    }
  }
  const double total = double(streams) * draws, expected = total / bins;
  double chi2 = 0;
  for (double c : count) chi2 += (c - expected) * (c - expected) / expected;
  // χ² with 255 degrees of freedom: mean 255, σ = √510 ≈ 22.6; P(χ² > 380) < 10⁻⁹.
  EXPECT_LT(chi2, 380.0);
  EXPECT_GT(chi2, 150.0);  // too uniform is not random either (P(χ² < 150) < 10⁻¹⁰)
  EXPECT_NEAR(sum / total, 0.5, 6.0 * std::sqrt(1.0 / 12.0 / total));
  EXPECT_NEAR(sumSq / total, 1.0 / 3.0, 6.0 * std::sqrt(4.0 / 45.0 / total));
  // Correlations of uniform pairs: σ = (1/12)/√pairs; 6σ bounds.
  EXPECT_NEAR(sumLag / double(pairsLag), 0.0, 6.0 / 12.0 / std::sqrt(double(pairsLag)));
  EXPECT_NEAR(sumCross / double(pairsCross), 0.0, 6.0 / 12.0 / std::sqrt(double(pairsCross)));
  // Distinct starting states: a hash collision among 2¹⁸ states of 2³² has
  // probability ≈ 0.8 per pair set (birthday: 2³⁵/2³² ≈ 8 expected), so allow
  // a handful, not a systematic repeat.
  std::sort(firstStates.begin(), firstStates.end());
  const long repeats = long(firstStates.size()) -
                       long(std::unique(firstStates.begin(), firstStates.end()) - firstStates.begin());
  EXPECT_LT(repeats, 40);
}

// The fixed-point R2 is the real-valued recurrence frac(½ + i/g), frac(½ + i/g²)
// to the 2⁻²⁴ of its output (plus the constants' rounding, i·2⁻³³), for
// indices far past where a float recurrence loses its digits; and every
// prefix of it is well spread: N points put at most 2 into any cell of a
// √N×√N grid (uniform random sets of 16…1024 points put 3…5 into their fullest cell).
TEST(SharedRng, R2PointsAreTheRecurrenceAndSpreadEvenly) {
  const double g = 1.32471795724474602596;
  for (uint32_t i : {0u, 1u, 2u, 1000u, 65535u, 1u << 20, 3000000u}) {
    const vec2 r = r2Point(i, 0u, 0u);
    double x = 0.5 + double(i) / g, y = 0.5 + double(i) / (g * g);
    x -= std::floor(x);
    y -= std::floor(y);
    const double tol = 0x1.0p-24 + double(i) * 0x1.0p-32;
    EXPECT_NEAR(r.x, x, tol) << i;
    EXPECT_NEAR(r.y, y, tol) << i;
  }
  for (int side : {4, 8, 16, 32}) {
    const int n = side * side;
    std::vector<int> cells(size_t(n), 0);
    for (int i = 0; i < n; ++i) {
      const vec2 r = r2Point(uint32_t(i), pcgHash(5u), pcgHash(6u));
      ASSERT_TRUE(r.x >= 0.0f && r.x < 1.0f && r.y >= 0.0f && r.y < 1.0f);
      ++cells[size_t(int(r.y * side) * side + int(r.x * side))];
    }
    EXPECT_LE(*std::max_element(cells.begin(), cells.end()), 2) << n << " points";
  }
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

// The path tracers' weight f·cos/pdf of a sampled direction, averaged, is the
// BRDF's directional albedo ∫ f cos dω — for a near-mirror lobe (e = 10³)
// too, at normal incidence (exactly ρ + ks) and at 70° (part of the lobe
// below the horizon: against a quadrature in the lobe's frame); no weight is
// NaN or infinite, and samples below the horizon are the ones dropped.
TEST(SharedBrdf, SamplingWeightAveragesToTheDirectionalAlbedoForANarrowLobe) {
  BrdfParams m;
  m.albedo = glm::vec3(0.3f);
  m.ks = glm::vec3(0.6f);
  m.exponent = 1000.0f;
  const glm::vec3 n(0, 0, 1);
  for (float thetaDeg : {0.0f, 70.0f}) {
    const float th = glm::radians(thetaDeg);
    const glm::vec3 wo(std::sin(th), 0.0f, std::cos(th));
    // Quadrature of the lobe part around r = reflect(wo): α up to where cos^e α < 1e-12.
    const glm::dvec3 r = glm::dvec3(reflectAbout(wo, n));
    const Basis f = makeBasis(glm::vec3(r));
    const double alphaMax = std::acos(std::pow(1e-12, 1.0 / m.exponent));
    const int na = 2000, np = 2000;
    double lobe = 0;
    for (int i = 0; i < na; ++i)
      for (int j = 0; j < np; ++j) {
        const double a = (i + 0.5) * alphaMax / na, phi = (j + 0.5) * 2 * M_PI / np;
        const glm::dvec3 w = glm::dvec3(f.t) * (std::sin(a) * std::cos(phi)) +
                             glm::dvec3(f.b) * (std::sin(a) * std::sin(phi)) + glm::dvec3(f.n) * std::cos(a);
        if (w.z <= 0) continue;
        lobe += (m.exponent + 2) / (2 * M_PI) * std::pow(std::cos(a), m.exponent) * w.z * std::sin(a) *
                (alphaMax / na) * (2 * M_PI / np);
      }
    const double expected = 0.3 + 0.6 * lobe;
    if (thetaDeg == 0.0f) {
      EXPECT_NEAR(lobe, 1.0, 1e-3);
    }
    uint32_t state = rngSeed(7u, uint32_t(thetaDeg), 3u);
    const int N = 200000;
    double sum = 0, sumSq = 0;
    for (int k = 0; k < N; ++k) {
      const glm::vec3 u(rngNext(state), rngNext(state), rngNext(state));
      const glm::vec3 wi = sampleBrdf(m, n, wo, u);
      const float pdf = brdfPdf(m, n, wo, wi);
      double w = 0;
      if (pdf > 0.0f && wi.z > 0.0f) w = double(evalBrdf(m, n, wo, wi).x) * wi.z / pdf;
      ASSERT_TRUE(std::isfinite(w)) << k;
      sum += w;
      sumSq += w * w;
    }
    const double mean = sum / N, sd = std::sqrt(std::max(0.0, sumSq / N - mean * mean) / N);
    EXPECT_NEAR(mean, expected, 5 * sd + 1e-6) << thetaDeg << " deg: sd " << sd;
  }
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
