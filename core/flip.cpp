// FLIP and HDR-FLIP (core/flip.h), from the papers: Andersson et al., HPG 2020,
// §3–4 (the colour pipeline: YCxCz, the contrast-sensitivity filters, CIELAB
// with the Hunt adjustment, HyAB, the remap; the feature pipeline: edges and
// points; their combination), and Ray Tracing Gems II, ch. 19 (HDR-FLIP: the
// exposure range and the tone curve).
#include "core/flip.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/magma.h"
#include "core/parallel.h"

namespace vgi {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Linear sRGB ↔ XYZ: the sRGB primaries with the D65 white at (0.31271, 0.32902), whose XYZ
// (Xn, 1, Zn) ≈ (0.950428545, 1, 1.088900371) is the white the papers' YCxCz and CIELAB use.
struct ColourSpace {
  double toXyz[3][3], toRgb[3][3], white[3];
  ColourSpace() {
    const double xy[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
    const double wx = 0.31271, wy = 0.32902;
    white[0] = wx / wy;
    white[1] = 1.0;
    white[2] = (1.0 - wx - wy) / wy;
    double p[3][3];  // columns: each primary's XYZ at Y = 1
    for (int c = 0; c < 3; ++c) {
      p[0][c] = xy[c][0] / xy[c][1];
      p[1][c] = 1.0;
      p[2][c] = (1.0 - xy[c][0] - xy[c][1]) / xy[c][1];
    }
    double inv[3][3];
    invert(p, inv);
    for (int r = 0; r < 3; ++r) {
      const double s = inv[r][0] * white[0] + inv[r][1] * white[1] + inv[r][2] * white[2];
      for (int k = 0; k < 3; ++k) toXyz[k][r] = p[k][r] * s;  // column r scaled by the primary's weight
    }
    invert(toXyz, toRgb);
  }
  static void invert(const double m[3][3], double out[3][3]) {
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        const int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
        out[r][c] = (m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1]) / det;
      }
  }
};

const ColourSpace& colourSpace() {
  static const ColourSpace cs;
  return cs;
}

void rgbToXyz(const float rgb[3], double xyz[3]) {
  const ColourSpace& cs = colourSpace();
  for (int r = 0; r < 3; ++r)
    xyz[r] = cs.toXyz[r][0] * rgb[0] + cs.toXyz[r][1] * rgb[1] + cs.toXyz[r][2] * rgb[2];
}

double labF(double t) {
  constexpr double d = 6.0 / 29.0;
  return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
}

// The contrast-sensitivity functions (§4.1): per channel of YCxCz, g(r) = Σ a √(π/b) exp(−π² r² / b)
// over one or two terms, r in degrees.
struct CsfTerm {
  double a, b;
};
const std::vector<CsfTerm> kCsf[3] = {{{1.0, 0.0047}},                 // Y'
                                      {{1.0, 0.0053}},                 // Cx
                                      {{34.1, 0.04}, {13.5, 0.025}}};  // Cz

// One 1D kernel of 2R + 1 taps, centre at R.
using Kernel = std::vector<float>;

// out = in convolved with k along x (rows) or y (columns), the borders clamped to the edge.
void convolve(const std::vector<float>& in, std::vector<float>& out, int w, int h, const Kernel& k,
              bool alongX, int threads) {
  const int r = int(k.size() / 2);
  out.assign(in.size(), 0.0f);
  parallelFor(size_t(h), 8, threads, [&](size_t y0, size_t y1) {
    for (size_t yy = y0; yy < y1; ++yy) {
      const int y = int(yy);
      float* o = &out[size_t(y) * size_t(w)];
      if (alongX) {
        // The row with r clamped texels either side, then tap by tap across it (vectorises as the
        // column pass does).
        const float* row = &in[size_t(y) * size_t(w)];
        std::vector<float> padded(size_t(w + 2 * r));
        for (int x = -r; x < w + r; ++x) padded[size_t(x + r)] = row[std::clamp(x, 0, w - 1)];
        for (int x = 0; x < w; ++x) o[x] = 0.0f;
        for (int j = 0; j <= 2 * r; ++j) {
          const float kj = k[size_t(j)];
          const float* src = &padded[size_t(j)];
          for (int x = 0; x < w; ++x) o[x] += kj * src[x];
        }
      } else {
        for (int x = 0; x < w; ++x) o[x] = 0.0f;
        for (int j = -r; j <= r; ++j) {
          const float kj = k[size_t(j + r)];
          const float* row = &in[size_t(std::clamp(y + j, 0, h - 1)) * size_t(w)];
          for (int x = 0; x < w; ++x) o[x] += kj * row[x];
        }
      }
    }
  });
}

// The kernels at one viewing condition.
struct FlipKernels {
  double ppd = 0;
  // Per channel, per term: the 1D Gaussian (normalised to sum 1) and the term's share of the 2D
  // kernel's sum (Σ shares = 1 per channel).
  std::vector<std::pair<Kernel, double>> csf[3];
  Kernel gauss, edge, point;  // the feature detectors' 1D factors
  explicit FlipKernels(double pixelsPerDegree) : ppd(pixelsPerDegree) {
    const int r = flip_detail::csfRadius(ppd);
    for (int c = 0; c < 3; ++c) {
      double total = 0.0;
      std::vector<std::pair<Kernel, double>> terms;
      for (const CsfTerm& t : kCsf[c]) {
        Kernel k(size_t(2 * r + 1));
        double sum = 0.0;
        for (int x = -r; x <= r; ++x) {
          const double deg = double(x) / ppd;
          const double v = std::exp(-kPi * kPi * deg * deg / t.b);
          k[size_t(x + r)] = float(v);
          sum += v;
        }
        for (float& v : k) v = float(double(v) / sum);
        const double share = t.a * std::sqrt(kPi / t.b) * sum * sum;  // the term's 2D sum
        terms.emplace_back(k, share);
        total += share;
      }
      for (auto& [k, share] : terms) share /= total;
      csf[c] = terms;
    }
    const double sigma = flip_detail::featureSigma(ppd);
    const int fr = flip_detail::featureRadius(ppd);
    gauss.resize(size_t(2 * fr + 1));
    edge.resize(gauss.size());
    point.resize(gauss.size());
    double gs = 0, ep = 0, pp = 0, pn = 0;
    std::vector<double> g(gauss.size()), e(gauss.size()), p(gauss.size());
    for (int x = -fr; x <= fr; ++x) {
      const size_t i = size_t(x + fr);
      g[i] = std::exp(-double(x) * x / (2.0 * sigma * sigma));
      e[i] = -double(x) * g[i];
      p[i] = (double(x) * x / (sigma * sigma) - 1.0) * g[i];
      gs += g[i];
      if (e[i] > 0) ep += e[i];
      (p[i] > 0 ? pp : pn) += p[i];
    }
    for (size_t i = 0; i < g.size(); ++i) {
      gauss[i] = float(g[i] / gs);
      edge[i] = float(e[i] / ep);  // antisymmetric: the negative weights sum to −1 as well
      point[i] = float(p[i] > 0 ? p[i] / pp : p[i] / -pn);
    }
  }
};

// One image's colour (filtered, as Hunt-adjusted CIELAB) and features.
struct FlipPlanes {
  std::vector<float> lab[3];
  std::vector<float> edges, points;
};

FlipPlanes planesOf(const std::vector<glm::vec3>& rgb, int w, int h, const FlipKernels& k, int threads) {
  const ColourSpace& cs = colourSpace();
  const size_t n = rgb.size();
  std::vector<float> ycc[3], luminance(n);
  for (auto& p : ycc) p.resize(n);
  parallelFor(n, 4096, threads, [&](size_t i0, size_t i1) {
    for (size_t i = i0; i < i1; ++i) {
      const float c[3] = {std::clamp(rgb[i].x, 0.0f, 1.0f), std::clamp(rgb[i].y, 0.0f, 1.0f),
                          std::clamp(rgb[i].z, 0.0f, 1.0f)};
      double xyz[3];
      rgbToXyz(c, xyz);
      const double x = xyz[0] / cs.white[0], y = xyz[1] / cs.white[1], z = xyz[2] / cs.white[2];
      ycc[0][i] = float(116.0 * y - 16.0);
      ycc[1][i] = float(500.0 * (x - y));
      ycc[2][i] = float(200.0 * (y - z));
      luminance[i] = float(y);
    }
  });
  // The contrast-sensitivity filters, term by term (each term's Gaussian is separable).
  std::vector<float> filtered[3], tmp, term;
  for (int c = 0; c < 3; ++c) {
    filtered[c].assign(n, 0.0f);
    for (const auto& [kernel, share] : k.csf[c]) {
      convolve(ycc[c], tmp, w, h, kernel, true, threads);
      convolve(tmp, term, w, h, kernel, false, threads);
      for (size_t i = 0; i < n; ++i) filtered[c][i] += float(share) * term[i];
    }
  }
  FlipPlanes out;
  for (auto& p : out.lab) p.resize(n);
  parallelFor(n, 4096, threads, [&](size_t i0, size_t i1) {
    for (size_t i = i0; i < i1; ++i) {
      const double y = (double(filtered[0][i]) + 16.0) / 116.0;
      const double xyz[3] = {(filtered[1][i] / 500.0 + y) * cs.white[0], y * cs.white[1],
                             (y - filtered[2][i] / 200.0) * cs.white[2]};
      float rgbc[3];
      for (int r = 0; r < 3; ++r)
        rgbc[r] = std::clamp(
            float(cs.toRgb[r][0] * xyz[0] + cs.toRgb[r][1] * xyz[1] + cs.toRgb[r][2] * xyz[2]), 0.0f, 1.0f);
      float lab[3];
      flip_detail::huntLab(rgbc, lab);
      for (int c = 0; c < 3; ++c) out.lab[c][i] = lab[c];
    }
  });
  flip_detail::features(luminance, w, h, k.ppd, out.edges, out.points, threads);
  return out;
}

// The LDR-FLIP map of two images already in [0, 1] (linear).
std::vector<float> ldrMap(const std::vector<glm::vec3>& test, const std::vector<glm::vec3>& ref, int w, int h,
                          const FlipKernels& k, int threads) {
  const FlipPlanes t = planesOf(test, w, h, k, threads), r = planesOf(ref, w, h, k, threads);
  const double cmax = flip_detail::colourMax(), pc = 0.4, pt = 0.95;
  std::vector<float> map(test.size());
  parallelFor(map.size(), 4096, threads, [&](size_t i0, size_t i1) {
    for (size_t i = i0; i < i1; ++i) {
      const double dl = double(t.lab[0][i]) - r.lab[0][i], da = double(t.lab[1][i]) - r.lab[1][i],
                   db = double(t.lab[2][i]) - r.lab[2][i];
      const double e = std::pow(std::abs(dl) + std::sqrt(da * da + db * db), 0.7);
      const double colour =
          e < pc * cmax ? e * pt / (pc * cmax) : pt + (e - pc * cmax) / (cmax - pc * cmax) * (1.0 - pt);
      const double feature = std::sqrt(
          std::max(std::abs(double(t.edges[i]) - r.edges[i]), std::abs(double(t.points[i]) - r.points[i])) /
          std::sqrt(2.0));
      map[i] = float(std::pow(std::min(colour, 1.0), 1.0 - feature));
    }
  });
  return map;
}

void checkPair(const Image& a, const Image& b, const FlipViewing& viewing) {
  viewing.check();
  if (a.width <= 0 || a.height <= 0 || b.width <= 0 || b.height <= 0) fail("FLIP: an image is empty");
  if (a.width != b.width || a.height != b.height)
    fail("FLIP: image sizes differ (", a.width, "x", a.height, " against ", b.width, "x", b.height, ")");
}

double luminanceOf(glm::vec3 c) {
  const ColourSpace& cs = colourSpace();
  return cs.toXyz[1][0] * c.x + cs.toXyz[1][1] * c.y + cs.toXyz[1][2] * c.z;
}

}  // namespace

double FlipViewing::pixelsPerDegree() const {
  return distance * (double(displayPixels) / displayWidth) * kPi / 180.0;
}

void FlipViewing::check() const {
  if (!(distance > 0.0) || !std::isfinite(distance))
    fail("--flip-distance ", distance, ": the viewing distance must be a finite number of metres > 0");
  if (!(displayWidth > 0.0) || !std::isfinite(displayWidth))
    fail("--flip-display-width ", displayWidth,
         ": the display's width must be a finite number of metres > 0");
  if (displayPixels < 1)
    fail("--flip-display-pixels ", displayPixels, ": the display's width in pixels must be >= 1");
  const double ppd = pixelsPerDegree();
  if (!(ppd <= 1000.0))
    fail("--flip-distance ", distance, ", --flip-display-width ", displayWidth, ", --flip-display-pixels ",
         displayPixels, ": ", ppd, " pixels per degree (at most 1000: FLIP's filters widen with them)");
}

namespace flip_detail {

int csfRadius(double ppd) { return int(std::ceil(3.0 * std::sqrt(0.04 / (2.0 * kPi * kPi)) * ppd)); }
double featureSigma(double ppd) { return 0.5 * 0.082 * ppd; }
int featureRadius(double ppd) { return int(std::ceil(3.0 * featureSigma(ppd))); }

void huntLab(const float rgb[3], float lab[3]) {
  const ColourSpace& cs = colourSpace();
  double xyz[3];
  rgbToXyz(rgb, xyz);
  const double fx = labF(xyz[0] / cs.white[0]), fy = labF(xyz[1] / cs.white[1]),
               fz = labF(xyz[2] / cs.white[2]);
  const double l = 116.0 * fy - 16.0;
  lab[0] = float(l);
  lab[1] = float(0.01 * l * 500.0 * (fx - fy));
  lab[2] = float(0.01 * l * 200.0 * (fy - fz));
}

double colourMax() {
  const float green[3] = {0, 1, 0}, blue[3] = {0, 0, 1};
  float g[3], b[3];
  huntLab(green, g);
  huntLab(blue, b);
  const double da = double(g[1]) - b[1], db = double(g[2]) - b[2];
  return std::pow(std::abs(double(g[0]) - b[0]) + std::sqrt(da * da + db * db), 0.7);
}

float toneMap(float x) {
  const double v = 0.6 * double(x);
  const double y = v * (2.51 * v + 0.03) / (v * (2.43 * v + 0.59) + 0.14);
  return float(std::clamp(y, 0.0, 1.0));
}

double toneMapInputFor085() {
  // 0.85 = v (2.51 v + 0.03) / (v (2.43 v + 0.59) + 0.14), v = 0.6 x: a quadratic in v.
  const double t = 0.85, a = 2.51 - t * 2.43, b = 0.03 - t * 0.59, c = -t * 0.14;
  const double v = (-b + std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a);
  return v / 0.6;
}

void features(const std::vector<float>& lum, int w, int h, double ppd, std::vector<float>& edges,
              std::vector<float>& points, int threads) {
  const FlipKernels k(ppd);
  // Each 2D detector is a derivative factor along one axis times the Gaussian along the other.
  std::vector<float> tmp, smoothX, ex, ey, px, py;
  convolve(lum, smoothX, w, h, k.gauss, true, threads);
  convolve(smoothX, ey, w, h, k.edge, false, threads);
  convolve(smoothX, py, w, h, k.point, false, threads);
  convolve(lum, tmp, w, h, k.edge, true, threads);
  convolve(tmp, ex, w, h, k.gauss, false, threads);
  convolve(lum, tmp, w, h, k.point, true, threads);
  convolve(tmp, px, w, h, k.gauss, false, threads);
  edges.resize(lum.size());
  points.resize(lum.size());
  for (size_t i = 0; i < lum.size(); ++i) {
    edges[i] = std::sqrt(ex[i] * ex[i] + ey[i] * ey[i]);
    points[i] = std::sqrt(px[i] * px[i] + py[i] * py[i]);
  }
}

}  // namespace flip_detail

FlipPooled poolFlip(const std::vector<float>& map, int width) {
  FlipPooled p;
  if (map.empty()) return p;
  double sum = 0.0;
  size_t top = 0;
  for (size_t i = 0; i < map.size(); ++i) {
    sum += map[i];
    if (map[i] > map[top]) top = i;
  }
  p.mean = sum / double(map.size());
  p.max = map[top];
  p.maxX = int(top % size_t(width));
  p.maxY = int(top / size_t(width));
  std::vector<float> sorted = map;
  std::sort(sorted.begin(), sorted.end());
  // The weighted percentiles: where the running sum of the sorted values passes q of their total.
  auto weighted = [&](double q) {
    if (!(sum > 0.0)) return 0.0;
    double run = 0.0;
    for (float v : sorted) {
      run += v;
      if (run >= q * sum) return double(v);
    }
    return double(sorted.back());
  };
  p.q1 = weighted(0.25);
  p.median = weighted(0.5);
  p.q3 = weighted(0.75);
  return p;
}

FlipResult ldrFlip(const Image& test, const Image& reference, const FlipViewing& viewing, int threads) {
  checkPair(test, reference, viewing);
  FlipResult r;
  r.width = test.width;
  r.height = test.height;
  r.pixelsPerDegree = viewing.pixelsPerDegree();
  const FlipKernels k(r.pixelsPerDegree);
  r.map = ldrMap(test.pixels, reference.pixels, test.width, test.height, k, threads);
  r.pooled = poolFlip(r.map, r.width);
  return r;
}

FlipResult hdrFlip(const Image& test, const Image& reference, const FlipViewing& viewing, int threads) {
  checkPair(test, reference, viewing);
  FlipResult r;
  r.hdr = true;
  r.width = test.width;
  r.height = test.height;
  r.pixelsPerDegree = viewing.pixelsPerDegree();
  // The exposure range from the reference's luminance.
  std::vector<double> lum(reference.pixels.size());
  for (size_t i = 0; i < lum.size(); ++i) lum[i] = std::max(0.0, luminanceOf(reference.pixels[i]));
  const double yMax = *std::max_element(lum.begin(), lum.end());
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  double yMedian = median(lum);
  if (!(yMedian > 0.0)) {
    std::vector<double> lit;
    for (double v : lum)
      if (v > 0.0) lit.push_back(v);
    yMedian = lit.empty() ? 0.0 : median(lit);
  }
  const double x = flip_detail::toneMapInputFor085();
  if (yMax > 0.0) {
    r.startExposure = std::log2(x / yMax);
    r.stopExposure = std::log2(x / yMedian);
  }
  r.exposures = std::max(2, int(std::ceil(r.stopExposure - r.startExposure)));
  const FlipKernels k(r.pixelsPerDegree);
  r.map.assign(test.pixels.size(), 0.0f);
  std::vector<glm::vec3> t(test.pixels.size()), ref(test.pixels.size());
  for (int e = 0; e < r.exposures; ++e) {
    const double exposure =
        r.startExposure + (r.stopExposure - r.startExposure) * double(e) / double(r.exposures - 1);
    const float scale = float(std::exp2(exposure));
    auto expose = [&](const std::vector<glm::vec3>& in, std::vector<glm::vec3>& out) {
      for (size_t i = 0; i < in.size(); ++i)
        out[i] = glm::vec3(flip_detail::toneMap(scale * std::max(in[i].x, 0.0f)),
                           flip_detail::toneMap(scale * std::max(in[i].y, 0.0f)),
                           flip_detail::toneMap(scale * std::max(in[i].z, 0.0f)));
    };
    expose(test.pixels, t);
    expose(reference.pixels, ref);
    const std::vector<float> m = ldrMap(t, ref, r.width, r.height, k, threads);
    for (size_t i = 0; i < m.size(); ++i) r.map[i] = std::max(r.map[i], m[i]);
  }
  r.pooled = poolFlip(r.map, r.width);
  return r;
}

nlohmann::json FlipResult::toJson() const {
  nlohmann::json j = {{"mean", pooled.mean},
                      {"median", pooled.median},
                      {"q1", pooled.q1},
                      {"q3", pooled.q3},
                      {"max", pooled.max},
                      {"max_pixel", {pooled.maxX, pooled.maxY}},
                      {"pixels_per_degree", pixelsPerDegree}};
  if (hdr) {
    j["start_exposure"] = startExposure;
    j["stop_exposure"] = stopExposure;
    j["exposures"] = exposures;
  }
  return j;
}

void writeFlipMap(const FlipResult& flip, const std::string& path) {
  Image img(flip.width, flip.height);
  const bool png = path.size() >= 4 && path.compare(path.size() - 4, 4, ".png") == 0;
  for (size_t i = 0; i < flip.map.size(); ++i) {
    const float v = std::clamp(flip.map[i], 0.0f, 1.0f);
    if (!png) {
      img.pixels[i] = glm::vec3(v);
      continue;
    }
    const float* c = kMagma[std::min(255, int(v * 255.0f + 0.5f))];
    // The table holds display (sRGB-encoded) colours; writeImage encodes linear values.
    img.pixels[i] = glm::vec3(srgbToLinear(c[0]), srgbToLinear(c[1]), srgbToLinear(c[2]));
  }
  writeImage(img, path);
}

}  // namespace vgi
