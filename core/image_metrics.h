// Image error metrics for `vgi diff`, `vgi compare` and the tests (b is the
// reference):
//   RMSE     sqrt(mean over pixels and channels of (a−b)²)
//   relMSE   mean of (a−b)² / (b² + ε), per pixel and channel. ε = 0.01 by
//            default (the usual choice for images of mean ~0.5); with
//            `relativeEpsilon` f it is (f · mean(b))², so the measure keeps
//            its meaning for a dim channel — the indirect light of the Cornell
//            box has mean ≈ 0.002, where a fixed 0.01 makes every error vanish
//   MAE      mean |a−b|
//   rel. MAE Σ|a − b| / Σ|b|, overall and per colour channel
//   energy   Σa / Σb per colour channel (1 = unbiased level; 1.16 = 16 % too bright)
//   SSIM     Wang et al. 2004 on tone-mapped (clamped, sRGB) luminance, 8×8
//            Gaussian-free box windows with stride 4 (mean SSIM).
#pragma once
#include <nlohmann/json_fwd.hpp>

#include "core/image.h"

namespace vgi {

struct DiffOptions {
  double epsilon = 0.01;       // relMSE's ε, used when relativeEpsilon is 0
  double relativeEpsilon = 0;  // > 0: ε = (relativeEpsilon · mean(b))²
};

struct ImageDiff {
  double rmse = 0, relMse = 0, mae = 0, ssim = 1;
  double relMae = 0;
  double epsilon = 0.01;  // the ε relMSE used
  double relMaeRgb[3] = {0, 0, 0};
  double energyRgb[3] = {1, 1, 1};
  double meanA[3] = {0, 0, 0}, meanB[3] = {0, 0, 0};  // per colour channel
  nlohmann::json toJson() const;
};

// Throws if the sizes differ, an image is empty or holds a non-finite value.
ImageDiff compareImages(const Image& a, const Image& b, const std::string& nameA = "A",
                        const std::string& nameB = "B", const DiffOptions& options = {});

// a − b per pixel and channel (sizes checked as in compareImages).
Image signedDifference(const Image& a, const Image& b);

// Writes a signed error image: .exr keeps the signed values; .png maps them to
// a diverging colour scale — red where a > b, blue where a < b, black where
// equal, full colour at |a − b| = `fullScale` (≤ 0: the 99th percentile of |a − b|).
void writeSignedError(const Image& difference, const std::string& path, float fullScale = 0);

}  // namespace vgi
