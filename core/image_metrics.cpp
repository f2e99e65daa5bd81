#include "core/image_metrics.h"

#include <cmath>

#include "core/error.h"

namespace vgi {

nlohmann::json ImageDiff::toJson() const {
  return {{"rmse", rmse}, {"relmse", relMse}, {"mae", mae}, {"rel_mae", relMae}, {"ssim", ssim}};
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

ImageDiff compareImages(const Image& a, const Image& b, const std::string& nameA,
                        const std::string& nameB) {
  if (a.width != b.width || a.height != b.height)
    fail("cannot compare images of different sizes: ", nameA, " is ", a.width, "x", a.height,
         ", ", nameB, " is ", b.width, "x", b.height);
  if (a.pixels.empty()) fail("cannot compare empty images (", nameA, ")");
  ImageDiff d;
  double se = 0, rel = 0, ae = 0, level = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      double x = a.pixels[i][k], r = b.pixels[i][k];
      if (!std::isfinite(x) || !std::isfinite(r))
        fail("image ", std::isfinite(x) ? nameB : nameA, " has a non-finite value at pixel (",
             i % a.width, ", ", i / a.width, ")");
      double e = x - r;
      se += e * e;
      rel += e * e / (r * r + 0.01);
      ae += std::abs(e);
      level += std::abs(r);
    }
  const double n = double(a.pixels.size()) * 3;
  d.rmse = std::sqrt(se / n);
  d.relMse = rel / n;
  d.mae = ae / n;
  d.relMae = level > 0 ? ae / level : (ae > 0 ? INFINITY : 0.0);
  d.ssim = meanSsim(a, b);
  return d;
}

}  // namespace vgi
