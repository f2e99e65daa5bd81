// vgi diff A B [--json]: error of image A against reference B.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "apps/commands.h"
#include "core/image_metrics.h"
#include "core/json_text.h"
#include "core/output_files.h"
#include "illum/run/render_job.h"
#include "illum/run/render_outputs.h"

namespace vgi::app {

namespace fs = std::filesystem;

void addDiffOptions(CLI::App* cmd, DiffOptions& d) {
  cmd->add_option("--epsilon", d.epsilon, "relMSE's epsilon: (a-b)^2 / (b^2 + epsilon)")
      ->capture_default_str();
  cmd->add_option(
      "--relative-epsilon", d.relativeEpsilon,
      "f > 0: relMSE's epsilon = (f x mean of the reference)^2, so dim images (an indirect channel) "
      "are measured on their own scale");
  cmd->add_option("--dark-tolerance", d.darkTolerance,
                  "leak: a pixel is dark where the reference's r+g+b is at most this x its mean (0: exactly "
                  "dark); leak = A's light there / the reference's light elsewhere")
      ->capture_default_str();
  auto* flip = cmd->add_option_function<std::string>(
      "--flip",
      [&d](const std::string& v) {
        d.flip = v == "off"   ? FlipMode::Off
                 : v == "ldr" ? FlipMode::Ldr
                 : v == "hdr" ? FlipMode::Hdr
                              : FlipMode::Auto;
      },
      "FLIP (core/flip.h): auto (HDR-FLIP and LDR-FLIP of linear images, LDR-FLIP of sRGB PNG/JPEG), ldr "
      "(linear values clamped to [0,1]), hdr or off");
  flip->check(CLI::IsMember({"auto", "ldr", "hdr", "off"}))->default_str("auto");
  d.flip = FlipMode::Auto;
  cmd->add_option("--flip-distance", d.viewing.distance, "FLIP's viewing distance, metres")
      ->capture_default_str();
  cmd->add_option("--flip-display-width", d.viewing.displayWidth, "FLIP's display width, metres")
      ->capture_default_str();
  cmd->add_option("--flip-display-pixels", d.viewing.displayPixels, "FLIP's display width, pixels")
      ->capture_default_str();
}

namespace {
// One number as printf's `spec` writes it, or "undefined" (a metric without a value: a ratio
// against a black reference), right-aligned in the same width.
std::string num(const char* spec, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, spec, v);
  if (std::isfinite(v)) return buf;
  std::string u = kUndefined;
  const size_t width = std::strlen(buf);
  return width > u.size() ? std::string(width - u.size(), ' ') + u : u;
}
}  // namespace

std::string diffLine(const ImageDiff& d) {
  const bool flip = d.hasFlipHdr || d.hasFlipLdr;
  return (flip ? num("%7.4f", d.flipMean()) + " " : std::string()) + num("%12.6g", d.relMse) + " " +
         num("%12.5f", d.relMae) + " " + num("%9.4f", d.ssim) + "   " + num("%.4f", d.relMaeRgb[0]) + " " +
         num("%.4f", d.relMaeRgb[1]) + " " + num("%.4f", d.relMaeRgb[2]) + "   " +
         num("%.3f", d.energyRgb[0]) + " " + num("%.3f", d.energyRgb[1]) + " " + num("%.3f", d.energyRgb[2]) +
         "   " + num("%9.3g", d.leak) + " (" + num("%.2f", d.darkFraction) + ")";
}
std::string diffHeader(bool flip) {
  return std::string(flip ? "   FLIP " : "") +
         "      relMSE     rel. MAE      SSIM   rel. MAE r / g / b       energy r / g / b (A/B)   leak (dark "
         "share)";
}

namespace {
// `vgi diff --frames N`: every frame's metrics, then the temporal ones (core/image_metrics.h).
void diffSequences(const std::string& a, const std::string& b, int frames, const std::string& aov,
                   const DiffOptions& options, bool json) {
  auto frameFile = [&](const std::string& path, int t) {
    const fs::path p(path);
    return frameStem((p.parent_path() / p.stem()).string(), t) + (aov.empty() ? "" : "." + aov) +
           p.extension().string();
  };
  std::vector<Image> ia, ib;
  nlohmann::json perFrame = nlohmann::json::array();
  if (!json) std::printf("frame %s\n", diffHeader(options.flip != FlipMode::Off).c_str());
  for (int t = 0; t < frames; ++t) {
    const std::string fa = frameFile(a, t), fb = frameFile(b, t);
    bool encodedA = false, encodedB = false;
    ia.push_back(readImage(fa, &encodedA));
    ib.push_back(readImage(fb, &encodedB));
    DiffOptions o = options;
    o.displayEncoded = encodedA || encodedB;
    ImageDiff d = compareImages(ia.back(), ib.back(), fa, fb, o);
    if (json)
      perFrame.push_back(d.toJson());
    else
      std::printf("%5d %s\n", t, diffLine(d).c_str());
  }
  SequenceDiff s = compareSequences(ia, ib, a, b);
  if (json) {
    nlohmann::json j = s.toJson();
    j["a"] = a;
    j["b"] = b;
    j["per_frame"] = perFrame;
    std::printf("%s\n", jsonText(j, 2).c_str());
  } else {
    std::printf("temporal error %s (frame-to-frame change: A %s, B %s; %d frames)\n",
                num("%.6g", s.temporalError).c_str(), num("%.6g", s.changeA).c_str(),
                num("%.6g", s.changeB).c_str(), s.frames);
  }
}
}  // namespace

void addDiffCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("diff",
                                 "Compare image A against reference B: RMSE, relMSE, (per-channel) rel. MAE, "
                                 "energy ratio, SSIM; |A-B| and signed A-B images");
  auto a = std::make_shared<std::string>();
  auto b = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto image = std::make_shared<std::string>();
  auto signedImage = std::make_shared<std::string>();
  auto exposure = std::make_shared<float>(1.0f);
  auto options = std::make_shared<DiffOptions>();
  cmd->add_option("A", *a, "image to measure")->required();
  cmd->add_option("B", *b, "reference image")->required();
  cmd->add_flag("--json", *json, "print JSON");
  addDiffOptions(cmd, *options);
  cmd->add_option("--image", *image, "write |A - B| per channel to this .exr/.png");
  cmd->add_option(
      "--signed-image", *signedImage,
      "write A - B to this .exr (signed) or .png (red: A > B, blue: A < B, full at the 99th percentile)");
  cmd->add_option("--exposure", *exposure, "exposure of the --image PNG")->capture_default_str();
  auto flipMap = std::make_shared<std::string>();
  cmd->add_option("--flip-map", *flipMap,
                  "write the FLIP map to this .png (magma: black 0 ... light yellow 1) or .exr (its values); "
                  "HDR-FLIP's where it is computed, else LDR-FLIP's");
  auto frames = std::make_shared<int>(1);
  cmd->add_option(
         "--frames", *frames,
         "N >= 2: A and B are animations as `vgi render --frames N -o A` writes them (A_0000.exr …); "
         "prints each frame's metrics and the temporal error of A's frame-to-frame change against B's")
      ->check(CLI::Range(1, 100000));
  auto aov = std::make_shared<std::string>();
  cmd->add_option(
      "--aov", *aov,
      "with --frames: compare this output of each frame (A_0000.NAME.exr …), as `vgi render --aov "
      "NAME` writes it");
  cmd->callback([=] {
    if (!aov->empty() && *frames < 2)
      fail("--aov ", *aov, " picks an output of each frame: only with --frames N >= 2");
    if (*frames > 1 && !(image->empty() && signedImage->empty() && flipMap->empty()))
      fail("--image, --signed-image and --flip-map write one frame's error: not with --frames ", *frames);
    if (!flipMap->empty() && options->flip == FlipMode::Off)
      fail("--flip-map ", *flipMap, " needs FLIP: not with --flip off");
    if (*frames > 1) return diffSequences(*a, *b, *frames, *aov, *options, *json);
    if (!image->empty()) checkOutputFile(*image, "--image");
    if (!signedImage->empty()) checkOutputFile(*signedImage, "--signed-image");
    if (!flipMap->empty()) checkOutputFile(*flipMap, "--flip-map");
    bool encodedA = false, encodedB = false;
    Image ia = readImage(*a, &encodedA), ib = readImage(*b, &encodedB);
    DiffOptions o = *options;
    o.displayEncoded = encodedA || encodedB;
    ImageDiff d = compareImages(ia, ib, *a, *b, o);
    if (!flipMap->empty()) writeFlipMap(d.hasFlipHdr ? d.flipHdr : d.flipLdr, *flipMap);
    Image e = signedDifference(ia, ib);
    if (!signedImage->empty()) writeSignedError(e, *signedImage);
    if (!image->empty()) {
      for (auto& p : e.pixels) p = glm::abs(p);
      writeImage(e, *image, *exposure);
    }
    if (*json) {
      nlohmann::json j = d.toJson();
      j["a"] = *a;
      j["b"] = *b;
      std::printf("%s\n", jsonText(j, 2).c_str());
    } else {
      std::printf(
          "rmse        %s\nmae         %s\nrelmse      %s (epsilon %s)\nrel_mae     %s (r %s, g %s, b %s)\n"
          "energy A/B  %s %s %s\nssim        %s\nleak        %s (dark share %s)\n",
          num("%.6g", d.rmse).c_str(), num("%.6g", d.mae).c_str(), num("%.6g", d.relMse).c_str(),
          num("%.3g", d.epsilon).c_str(), num("%.6g", d.relMae).c_str(), num("%.4f", d.relMaeRgb[0]).c_str(),
          num("%.4f", d.relMaeRgb[1]).c_str(), num("%.4f", d.relMaeRgb[2]).c_str(),
          num("%.4f", d.energyRgb[0]).c_str(), num("%.4f", d.energyRgb[1]).c_str(),
          num("%.4f", d.energyRgb[2]).c_str(), num("%.6f", d.ssim).c_str(), num("%.6g", d.leak).c_str(),
          num("%.4f", d.darkFraction).c_str());
      auto flipLine = [](const char* name, const FlipResult& f) {
        std::printf("flip %s    mean %.4f  median %.4f  quartiles %.4f %.4f  max %.4f at (%d, %d)", name,
                    f.pooled.mean, f.pooled.median, f.pooled.q1, f.pooled.q3, f.pooled.max, f.pooled.maxX,
                    f.pooled.maxY);
        if (f.hdr)
          std::printf("  (exposures %.2f to %.2f, %d)", f.startExposure, f.stopExposure, f.exposures);
        std::printf("\n");
      };
      if (d.hasFlipLdr) flipLine("ldr", d.flipLdr);
      if (d.hasFlipHdr) flipLine("hdr", d.flipHdr);
      if (d.hasFlipLdr || d.hasFlipHdr)
        std::printf("flip viewing %.3g m from %.3g m of %d pixels: %.2f pixels per degree\n",
                    o.viewing.distance, o.viewing.displayWidth, o.viewing.displayPixels,
                    o.viewing.pixelsPerDegree());
    }
  });
}

}  // namespace vgi::app
