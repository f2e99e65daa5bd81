// FLIP, the perceptual difference of an image against its reference as it is
// seen flipping between them on a display (Andersson, Nilsson, Akenine-Möller,
// Oskarsson, Åström and Fairchild, "FLIP: A Difference Evaluator for
// Alternating Images", HPG 2020), and HDR-FLIP (Andersson et al.,
// "Visualizing and Communicating Errors in Rendered Images", Ray Tracing Gems
// II, 2021) — implemented from the papers (the steps and constants pinned in
// the project's notes on them), not from any implementation's code.
//
// LDR-FLIP of two linear-RGB images in [0, 1], per pixel:
//   colour: linear RGB → XYZ (sRGB primaries, D65) → YCxCz; each channel
//     filtered by its contrast-sensitivity function (a sum of one or two
//     Gaussians in visual degrees at the viewing condition's pixels per
//     degree; §4.1 of the paper), back to linear RGB clamped to [0, 1], to
//     CIELAB with the Hunt adjustment (a, b scaled by 0.01 L), the HyAB
//     distance raised to 0.7 and remapped to [0, 1] (cmax: that of pure green
//     against pure blue; pc = 0.4, pt = 0.95) — ΔEc;
//   features: edges (first Gaussian derivative) and points (second) of each
//     image's luminance Y/Yn, σ = ½ · 0.082° · ppd; ΔEf = (max(|Δ‖edge‖|,
//     |Δ‖point‖|) / √2)^0.5;
//   FLIP = ΔEc^(1 − ΔEf).
// HDR-FLIP: both images exposed by 2^e and tone-mapped (the ACES filmic fit
// after a 0.6 pre-exposure), LDR-FLIP at each of a range of exposures e from
// log2(x / Ymax) to log2(x / Ymedian) of the reference (x: the input the tone
// curve maps to 0.85), at least 2 and one per stop, the per-pixel maximum.
// A reference with more than half its pixels black takes the median of its
// non-black ones (the authors' tool is known to fail there); an all-black one
// a single exposure of 0 (twice).
//
// Pooled: the mean (the number papers print), the weighted median and
// quartiles (the value where the running sum of the sorted values passes ½,
// ¼ and ¾ of their total), and the maximum with its pixel.
#pragma once
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "core/image.h"

namespace vgi {

// Where the images are seen from: the papers' default 0.7 m from a 0.7 m wide
// display of 3840 pixels, ≈ 67 pixels per degree.
struct FlipViewing {
  double distance = 0.7;      // metres, eye to display
  double displayWidth = 0.7;  // metres
  int displayPixels = 3840;   // pixels across that width
  double pixelsPerDegree() const;
  // Throws, naming the option (--flip-distance, --flip-display-width, --flip-display-pixels), unless
  // each is positive and finite and the pixels per degree are at most 1000 (the filters grow with
  // them: 1000 is a 136-pixel radius).
  void check() const;
};

struct FlipPooled {
  double mean = 0, median = 0, q1 = 0, q3 = 0, max = 0;
  int maxX = 0, maxY = 0;  // the maximum's pixel (row 0 = top)
};

struct FlipResult {
  bool hdr = false;
  int width = 0, height = 0;
  std::vector<float> map;  // per pixel, row 0 = top, in [0, 1]
  FlipPooled pooled;
  double pixelsPerDegree = 0;
  // HDR-FLIP only: the exposures (stops) the maximum was taken over.
  double startExposure = 0, stopExposure = 0;
  int exposures = 0;
  nlohmann::json toJson() const;
};

// LDR-FLIP of `test` against `reference` (linear RGB, each clamped to [0, 1]). Throws if the sizes
// differ or an image is empty. threads: 0 = all cores.
FlipResult ldrFlip(const Image& test, const Image& reference, const FlipViewing& viewing = {},
                   int threads = 0);
// HDR-FLIP of two linear HDR images.
FlipResult hdrFlip(const Image& test, const Image& reference, const FlipViewing& viewing = {},
                   int threads = 0);

// The pooled statistics of a FLIP map.
FlipPooled poolFlip(const std::vector<float>& map, int width);

// Writes the map: .png in the magma colour map (0 black … 1 light yellow), .exr its values.
void writeFlipMap(const FlipResult& flip, const std::string& path);

// The pieces the tests check against the papers.
namespace flip_detail {
// The contrast-sensitivity filters' radius in pixels: ⌈3 √(0.04 / (2π²)) · ppd⌉.
int csfRadius(double ppd);
// The feature detectors' σ and radius ⌈3σ⌉ in pixels.
double featureSigma(double ppd);
int featureRadius(double ppd);
// Linear RGB → CIELAB (D65) with the Hunt adjustment.
void huntLab(const float rgb[3], float lab[3]);
// HyAB^0.7 between pure green and pure blue: the colour difference's normaliser.
double colourMax();
// The ACES fit after the 0.6 pre-exposure, clamped to [0, 1], and the input it maps to 0.85.
float toneMap(float x);
double toneMapInputFor085();
// The edge and point magnitudes of a luminance image (row 0 = top, clamped at the borders).
void features(const std::vector<float>& luminance, int width, int height, double ppd,
              std::vector<float>& edges, std::vector<float>& points, int threads);
}  // namespace flip_detail

}  // namespace vgi
