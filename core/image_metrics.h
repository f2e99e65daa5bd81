// Image error metrics for `vgi diff`, `vgi compare` and the tests (b is the
// reference):
//   RMSE     sqrt(mean over pixels and channels of (a−b)²)
//   relMSE   mean of (a−b)² / (b² + ε), per pixel and channel. ε = 0.01 by
//            default (the usual choice for images of mean ~0.5); with
//            `relativeEpsilon` f it is (f · mean(b))², so the measure keeps
//            its meaning for a dim channel — the indirect light of the Cornell
//            box has mean ≈ 0.002, where a fixed 0.01 makes every error vanish
//            relMSE trimmed: the same mean with the top 0.1 % of the pixels' errors (the sum
//            over a pixel's channels) dropped, the variant papers print beside it (a few
//            fireflies then do not decide a comparison); no pixel is dropped below 1000 pixels
//   MAE      mean |a−b|
//   rel. MAE Σ|a − b| / Σ|b|, overall and per colour channel
//   energy   Σa / Σb per colour channel (1 = unbiased level; 1.16 = 16 % too bright)
//   SSIM     Wang et al. 2004 on tone-mapped (clamped, sRGB) luminance, 8×8
//            Gaussian-free box windows with stride 4 (mean SSIM).
//   FLIP     the perceptual difference (core/flip.h): LDR-FLIP and HDR-FLIP, each pooled
//            (mean, weighted median and quartiles, max and where), with `flip`: auto
//            gives both for linear images and LDR-FLIP alone for display-encoded ones
//            (an sRGB PNG or JPEG, decoded: `displayEncoded`); off (the library's
//            default: the tests' thousands of comparisons do not need it) none.
//   leak     Σ_dark (a_r + a_g + a_b) / Σ_lit (b_r + b_g + b_b): the light a puts
//            where the reference is dark, as a fraction of the reference's light
//            elsewhere. A pixel is dark where b_r + b_g + b_b ≤ τ · its mean over
//            the image (τ = `darkTolerance`, 0 by default: exactly dark, as the
//            exact counterpart leaves a room no light path reaches); lit
//            otherwise. Measured on the indirect channel of a scene with a dark
//            room behind a wall, it is the light leaking through the wall;
//            `darkFraction` is the share of dark pixels (0: the leak is 0 and
//            means nothing).
//
// Over an animation (compareSequences), with Δx_t = x_t − x_{t−1} per pixel and
// channel for t ≥ 1:
//   temporal error  Σ_t Σ |Δa_t − Δb_t| / Σ_{t≥1} Σ |b_t|: how far the method's
//            frame-to-frame change is from the exact one's, relative to the
//            level — 0 for any two sequences that change alike (a constant
//            image against a constant image); the static error of each frame
//            does not enter. A converged method measures flicker and voxel
//            snapping; a few-sample method also its noise (two independent noisy
//            frames differ by √2 × the noise), unless its seeds repeat per frame.
//   change   Σ_t Σ |Δx_t| / Σ_{t≥1} Σ |x_t| of each sequence alone (`changeA`,
//            `changeB`): how much each one moves from frame to frame.
//
// A ratio whose denominator is 0 has no value: rel. MAE, energy and relMSE with a relative ε
// against a black reference, the leak where nothing is lit, the temporal metrics of a dark
// sequence. It is +inf or NaN here (0 where the numerator is 0 too) and "undefined" in JSON
// (toJson, core/json_text.h) and in `vgi diff`'s text.
#pragma once
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "core/flip.h"
#include "core/image.h"

namespace vgi {

enum class FlipMode { Off, Auto, Ldr, Hdr };

struct DiffOptions {
  double epsilon = 0.01;       // relMSE's ε, used when relativeEpsilon is 0
  double relativeEpsilon = 0;  // > 0: ε = (relativeEpsilon · mean(b))²
  double darkTolerance = 0;    // leak: dark where b ≤ this × mean(b) (sum of the channels)
  FlipMode flip = FlipMode::Off;
  FlipViewing viewing;          // FLIP's viewing condition
  bool displayEncoded = false;  // the images were read from display-encoded files (auto: LDR only)
};

struct ImageDiff {
  double rmse = 0, relMse = 0, mae = 0, ssim = 1;
  double relMseTrimmed = 0;  // relMSE without the top 0.1 % of the pixels' errors
  double relMae = 0;
  double epsilon = 0.01;  // the ε relMSE used
  double relMaeRgb[3] = {0, 0, 0};
  double energyRgb[3] = {1, 1, 1};
  double meanA[3] = {0, 0, 0}, meanB[3] = {0, 0, 0};  // per colour channel
  double leak = 0, darkFraction = 0;
  bool hasFlipLdr = false, hasFlipHdr = false;
  FlipResult flipLdr, flipHdr;  // with their maps
  // HDR-FLIP's mean where it was computed, else LDR-FLIP's, else NaN: the one FLIP a table shows.
  double flipMean() const;
  nlohmann::json toJson() const;
};

struct SequenceDiff {
  int frames = 0;
  double temporalError = 0, changeA = 0, changeB = 0;
  nlohmann::json toJson() const;
};

// Throws if the sizes differ, an image is empty or holds a non-finite value.
ImageDiff compareImages(const Image& a, const Image& b, const std::string& nameA = "A",
                        const std::string& nameB = "B", const DiffOptions& options = {});

// The temporal metrics of two animations of equal length (≥ 2 frames), frame t of a against frame t
// of b (sizes and values checked as in compareImages).
SequenceDiff compareSequences(const std::vector<Image>& a, const std::vector<Image>& b,
                              const std::string& nameA = "A", const std::string& nameB = "B");

// a − b per pixel and channel (sizes checked as in compareImages).
Image signedDifference(const Image& a, const Image& b);

// Writes a signed error image: .exr keeps the signed values; .png maps them to
// a diverging colour scale — red where a > b, blue where a < b, black where
// equal, full colour at |a − b| = `fullScale` (≤ 0: the 99th percentile of |a − b|).
void writeSignedError(const Image& difference, const std::string& path, float fullScale = 0);

}  // namespace vgi
