// vgi diff A B [--json]: error of image A against reference B.
#include <cstdio>

#include "apps/commands.h"
#include "core/image_metrics.h"

namespace vgi::app {

void addDiffCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("diff", "Compare image A against reference B: RMSE, relMSE, MAE, SSIM (and |A-B| with --image)");
  auto a = std::make_shared<std::string>();
  auto b = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto image = std::make_shared<std::string>();
  auto exposure = std::make_shared<float>(1.0f);
  cmd->add_option("A", *a, "image to measure")->required();
  cmd->add_option("B", *b, "reference image")->required();
  cmd->add_flag("--json", *json, "print JSON");
  cmd->add_option("--image", *image, "write |A - B| per channel to this .exr/.png");
  cmd->add_option("--exposure", *exposure, "exposure of the --image PNG")->capture_default_str();
  cmd->callback([=] {
    Image ia = readImage(*a), ib = readImage(*b);
    ImageDiff d = compareImages(ia, ib, *a, *b);
    if (!image->empty()) {
      Image e(ia.width, ia.height);
      for (size_t i = 0; i < e.pixels.size(); ++i) e.pixels[i] = glm::abs(ia.pixels[i] - ib.pixels[i]);
      writeImage(e, *image, *exposure);
    }
    if (*json) {
      nlohmann::json j = d.toJson();
      j["a"] = *a;
      j["b"] = *b;
      std::printf("%s\n", j.dump(2).c_str());
    } else {
      std::printf("rmse    %.6g\nrelmse  %.6g\nmae     %.6g\nrel_mae %.6g\nssim    %.6f\n", d.rmse, d.relMse, d.mae, d.relMae, d.ssim);
    }
  });
}

}  // namespace vgi::app
