#include "core/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/error.h"
#include "core/json_text.h"

namespace vgi {

// A metric whose denominator is 0 (a black reference, nothing lit, no change) has no value: it is
// written "undefined" (core/json_text.h), not null.
nlohmann::json ImageDiff::toJson() const {
  auto num = [](double v) { return finiteOrUndefined(v); };
  auto rgb = [&](const double* v) { return nlohmann::json{num(v[0]), num(v[1]), num(v[2])}; };
  nlohmann::json j = {{"rmse", num(rmse)},
                      {"relmse", num(relMse)},
                      {"relmse_epsilon", num(epsilon)},
                      {"relmse_trimmed", num(relMseTrimmed)},
                      {"mae", num(mae)},
                      {"rel_mae", num(relMae)},
                      {"rel_mae_rgb", rgb(relMaeRgb)},
                      {"energy_rgb", rgb(energyRgb)},
                      {"mean_a_rgb", rgb(meanA)},
                      {"mean_b_rgb", rgb(meanB)},
                      {"ssim", num(ssim)},
                      {"leak", num(leak)},
                      {"dark_fraction", num(darkFraction)}};
  if (hasFlipLdr) j["flip"]["ldr"] = flipLdr.toJson();
  if (hasFlipHdr) j["flip"]["hdr"] = flipHdr.toJson();
  return j;
}

nlohmann::json SequenceDiff::toJson() const {
  return {{"frames", frames},
          {"temporal_error", finiteOrUndefined(temporalError)},
          {"change_a", finiteOrUndefined(changeA)},
          {"change_b", finiteOrUndefined(changeB)}};
}

namespace {
double meanSsim(const Image& a, const Image& b) {
  const int w = a.width, h = a.height;
  auto tone = [](glm::vec3 c) { return double(linearToSrgb(luminance(c))); };
  std::vector<double> la(size_t(w) * h), lb(size_t(w) * h);
  for (size_t i = 0; i < la.size(); ++i) {
    la[i] = tone(a.pixels[i]);
    lb[i] = tone(b.pixels[i]);
  }
  const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;  // dynamic range L = 1
  const int win = std::min({8, w, h}), stride = std::max(1, win / 2);
  double sum = 0;
  long n = 0;
  for (int y0 = 0; y0 + win <= h; y0 += stride)
    for (int x0 = 0; x0 + win <= w; x0 += stride) {
      double ma = 0, mb = 0;
      for (int y = y0; y < y0 + win; ++y)
        for (int x = x0; x < x0 + win; ++x) {
          ma += la[size_t(y) * w + x];
          mb += lb[size_t(y) * w + x];
        }
      const double cnt = double(win) * win;
      ma /= cnt;
      mb /= cnt;
      double va = 0, vb = 0, cov = 0;
      for (int y = y0; y < y0 + win; ++y)
        for (int x = x0; x < x0 + win; ++x) {
          double da = la[size_t(y) * w + x] - ma, db = lb[size_t(y) * w + x] - mb;
          va += da * da;
          vb += db * db;
          cov += da * db;
        }
      va /= cnt - 1;
      vb /= cnt - 1;
      cov /= cnt - 1;
      sum += ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
      ++n;
    }
  return n ? sum / n : 1.0;
}
}  // namespace

namespace {
// num / den, with 0 / 0 = 0 and x / 0 = ∞ for x > 0.
double ratio(double num, double den) { return den > 0 ? num / den : (num > 0 ? INFINITY : 0.0); }

// Throws naming the image (a's or b's) and the pixel when a value of either is not finite.
void checkFinitePair(double x, double r, const std::string& nameA, const std::string& nameB, size_t pixel,
                     int width) {
  if (!std::isfinite(x) || !std::isfinite(r))
    fail("image ", std::isfinite(x) ? nameB : nameA, " has a non-finite value at pixel (", pixel % width,
         ", ", pixel / width, ")");
}

void checkComparable(const Image& a, const Image& b, const std::string& nameA, const std::string& nameB) {
  if (a.width != b.width || a.height != b.height)
    fail("cannot compare images of different sizes: ", nameA, " is ", a.width, "x", a.height, ", ", nameB,
         " is ", b.width, "x", b.height);
  if (a.pixels.empty()) fail("cannot compare empty images (", nameA, ")");
}
}  // namespace

ImageDiff compareImages(const Image& a, const Image& b, const std::string& nameA, const std::string& nameB,
                        const DiffOptions& options) {
  checkComparable(a, b, nameA, nameB);
  if (!(options.epsilon > 0) || !(options.relativeEpsilon >= 0) || !std::isfinite(options.relativeEpsilon))
    fail("relMSE epsilon ", options.epsilon, " / relative ", options.relativeEpsilon,
         ": epsilon must be > 0, the relative factor >= 0");
  if (!(options.darkTolerance >= 0) || !std::isfinite(options.darkTolerance))
    fail("the leak's dark tolerance ", options.darkTolerance, " must be a finite number >= 0");
  double sumA[3] = {0, 0, 0}, sumB[3] = {0, 0, 0}, absErr[3] = {0, 0, 0};
  for (size_t i = 0; i < a.pixels.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      double x = a.pixels[i][k], r = b.pixels[i][k];
      checkFinitePair(x, r, nameA, nameB, i, a.width);
      sumA[k] += x;
      sumB[k] += std::abs(r);
      absErr[k] += std::abs(x - r);
    }
  const double n = double(a.pixels.size()) * 3;
  ImageDiff d;
  d.epsilon = options.epsilon;
  if (options.relativeEpsilon > 0) {
    const double mean = (sumB[0] + sumB[1] + sumB[2]) / n;
    d.epsilon = std::max(1e-30, options.relativeEpsilon * options.relativeEpsilon * mean * mean);
  }
  double se = 0, rel = 0;
  std::vector<double> relPixel(a.pixels.size());  // per pixel: the sum over its channels
  for (size_t i = 0; i < a.pixels.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      double r = b.pixels[i][k], e = a.pixels[i][k] - r;
      se += e * e;
      const double q = e * e / (r * r + d.epsilon);
      rel += q;
      relPixel[i] += q;
    }
  // The trimmed relMSE: the top 0.1 % of the pixels' errors dropped (none below 1000 pixels).
  const size_t dropped = relPixel.size() / 1000, kept = relPixel.size() - dropped;
  std::nth_element(relPixel.begin(), relPixel.begin() + std::ptrdiff_t(kept - 1), relPixel.end());
  double relKept = 0;
  for (size_t i = 0; i < kept; ++i) relKept += relPixel[i];
  d.relMseTrimmed = relKept / (double(kept) * 3);
  const double ae = absErr[0] + absErr[1] + absErr[2], level = sumB[0] + sumB[1] + sumB[2];
  d.rmse = std::sqrt(se / n);
  d.relMse = rel / n;
  if (dropped == 0) d.relMseTrimmed = d.relMse;  // the same sum, not one rounded another way
  // ε relative to a black reference's mean is 0: relMSE has no scale (it was 1e27 through the floor).
  if (options.relativeEpsilon > 0 && level == 0) {
    d.epsilon = NAN;
    d.relMse = d.relMseTrimmed = se == 0 ? 0.0 : NAN;
  }
  d.mae = ae / n;
  d.relMae = ratio(ae, level);
  for (int k = 0; k < 3; ++k) {
    d.relMaeRgb[k] = ratio(absErr[k], sumB[k]);
    d.energyRgb[k] = sumB[k] > 0 ? sumA[k] / sumB[k] : (sumA[k] == 0 ? 1.0 : INFINITY);
    d.meanA[k] = sumA[k] / double(a.pixels.size());
    d.meanB[k] = sumB[k] / double(a.pixels.size());
  }
  d.ssim = meanSsim(a, b);
  // The leak: a's light where b is dark, over b's light where it is not.
  const double darkLevel = options.darkTolerance * level / double(a.pixels.size());
  double leaked = 0, lit = 0;
  long dark = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    const glm::vec3 &pa = a.pixels[i], &pb = b.pixels[i];
    const double sb = double(pb.x) + pb.y + pb.z;
    if (sb <= darkLevel) {
      ++dark;
      leaked += double(pa.x) + pa.y + pa.z;
    } else {
      lit += sb;
    }
  }
  d.darkFraction = double(dark) / double(a.pixels.size());
  d.leak = ratio(leaked, lit);
  const bool ldr = options.flip == FlipMode::Ldr || (options.flip == FlipMode::Auto),
             hdr =
                 options.flip == FlipMode::Hdr || (options.flip == FlipMode::Auto && !options.displayEncoded);
  if (ldr) {
    d.flipLdr = ldrFlip(a, b, options.viewing);
    d.hasFlipLdr = true;
  }
  if (hdr) {
    d.flipHdr = hdrFlip(a, b, options.viewing);
    d.hasFlipHdr = true;
  }
  return d;
}

double ImageDiff::flipMean() const {
  return hasFlipHdr ? flipHdr.pooled.mean : (hasFlipLdr ? flipLdr.pooled.mean : NAN);
}

SequenceDiff compareSequences(const std::vector<Image>& a, const std::vector<Image>& b,
                              const std::string& nameA, const std::string& nameB) {
  if (a.size() != b.size() || a.size() < 2)
    fail("a temporal comparison needs two animations of the same length, at least 2 frames: ", nameA, " has ",
         a.size(), ", ", nameB, " ", b.size());
  double err = 0, changeA = 0, changeB = 0, levelA = 0, levelB = 0;
  for (size_t t = 0; t < a.size(); ++t) {
    const std::string frame = " frame " + std::to_string(t);
    checkComparable(a[t], b[t], nameA + frame, nameB + frame);
    checkComparable(a[t], a[0], nameA + frame, nameA + " frame 0");
    for (size_t i = 0; i < a[t].pixels.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        const double x = a[t].pixels[i][k], r = b[t].pixels[i][k];
        checkFinitePair(x, r, nameA + frame, nameB + frame, i, a[t].width);
        if (t == 0) continue;
        const double da = x - a[t - 1].pixels[i][k], db = r - b[t - 1].pixels[i][k];
        err += std::abs(da - db);
        changeA += std::abs(da);
        changeB += std::abs(db);
        levelA += std::abs(x);
        levelB += std::abs(r);
      }
  }
  SequenceDiff s;
  s.frames = int(a.size());
  s.temporalError = ratio(err, levelB);
  s.changeA = ratio(changeA, levelA);
  s.changeB = ratio(changeB, levelB);
  return s;
}

Image signedDifference(const Image& a, const Image& b) {
  checkComparable(a, b, "A", "B");
  Image d(a.width, a.height);
  for (size_t i = 0; i < d.pixels.size(); ++i) d.pixels[i] = a.pixels[i] - b.pixels[i];
  return d;
}

void writeSignedError(const Image& difference, const std::string& path, float fullScale) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (auto& c : ext) c = char(std::tolower(c));
  if (ext == ".exr") return writeImage(difference, path);
  if (difference.pixels.empty()) fail("cannot write the error image '", path, "': the image is empty");
  if (!(fullScale > 0)) {
    std::vector<float> mags;
    mags.reserve(difference.pixels.size());
    for (auto& p : difference.pixels) mags.push_back(std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}));
    const size_t k = std::min(mags.size() - 1, size_t(0.99 * double(mags.size())));
    std::nth_element(mags.begin(), mags.begin() + long(k), mags.end());
    fullScale = mags[k] > 0 ? mags[k] : 1.0f;
  }
  // Luminance of the signed error, shown red (positive) or blue (negative) at
  // display values (writeImage's sRGB encoding applies).
  Image shown(difference.width, difference.height);
  for (size_t i = 0; i < shown.pixels.size(); ++i) {
    const glm::vec3 e = difference.pixels[i];
    const float v = std::clamp((e.x + e.y + e.z) / (3.0f * fullScale), -1.0f, 1.0f);
    shown.pixels[i] = v >= 0 ? glm::vec3(v, 0.1f * v, 0.0f) : glm::vec3(0.0f, 0.3f * -v, -v);
  }
  writeImage(shown, path);
}

}  // namespace vgi
