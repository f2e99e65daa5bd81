// Image error metrics for `vgi diff` and the tests.
//   RMSE   sqrt(mean over pixels and channels of (a−b)²)
//   relMSE mean of (a−b)² / (b² + 0.01), per pixel and channel (b = reference)
//   MAE    mean |a−b|
//   SSIM   Wang et al. 2004 on tone-mapped (clamped, sRGB) luminance, 8×8
//          Gaussian-free box windows with stride 4 (mean SSIM).
#pragma once
#include <nlohmann/json.hpp>

#include "core/image.h"

namespace vgi {

struct ImageDiff {
  double rmse = 0, relMse = 0, mae = 0, ssim = 1;
  // Σ|a − b| / Σ|b|: the error relative to the reference's own level, for dim
  // images (e.g. an indirect channel) where relMSE's +0.01 hides everything.
  double relMae = 0;
  nlohmann::json toJson() const;
};

// b is the reference. Throws if the sizes differ or an image is empty.
ImageDiff compareImages(const Image& a, const Image& b, const std::string& nameA = "A",
                        const std::string& nameB = "B");

}  // namespace vgi
