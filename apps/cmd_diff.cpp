// vgi diff A B [--json]: error of image A against reference B.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "apps/commands.h"
#include "core/image_metrics.h"
#include "core/json_text.h"
#include "core/output_files.h"

namespace vgi::app {

void addDiffOptions(CLI::App* cmd, DiffOptions& d) {
  cmd->add_option("--epsilon", d.epsilon, "relMSE's epsilon: (a-b)^2 / (b^2 + epsilon)")
      ->capture_default_str();
  cmd->add_option(
      "--relative-epsilon", d.relativeEpsilon,
      "f > 0: relMSE's epsilon = (f x mean of the reference)^2, so dim images (an indirect channel) "
      "are measured on their own scale");
}

std::string diffLine(const ImageDiff& d) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%12.6g %12.5f %9.4f   %.4f %.4f %.4f   %.3f %.3f %.3f", d.relMse, d.relMae,
                d.ssim, d.relMaeRgb[0], d.relMaeRgb[1], d.relMaeRgb[2], d.energyRgb[0], d.energyRgb[1],
                d.energyRgb[2]);
  return buf;
}
const char* diffHeader() {
  return "      relMSE     rel. MAE      SSIM   rel. MAE r / g / b       energy r / g / b (A/B)";
}

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
  cmd->callback([=] {
    if (!image->empty()) checkOutputFile(*image, "--image");
    if (!signedImage->empty()) checkOutputFile(*signedImage, "--signed-image");
    Image ia = readImage(*a), ib = readImage(*b);
    ImageDiff d = compareImages(ia, ib, *a, *b, *options);
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
          "rmse        %.6g\nmae         %.6g\nrelmse      %.6g (epsilon %.3g)\nrel_mae     %.6g (r %.4f, g "
          "%.4f, b %.4f)\nenergy A/B  %.4f %.4f %.4f\nssim        %.6f\n",
          d.rmse, d.mae, d.relMse, d.epsilon, d.relMae, d.relMaeRgb[0], d.relMaeRgb[1], d.relMaeRgb[2],
          d.energyRgb[0], d.energyRgb[1], d.energyRgb[2], d.ssim);
    }
  });
}

}  // namespace vgi::app
