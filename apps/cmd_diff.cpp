// vgi diff A B [--json]: error of image A against reference B.
#include <cstdio>

#include "apps/commands.h"
#include "core/image_metrics.h"

namespace vgi::app {

void addDiffCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("diff", "Compare image A against reference B: RMSE, relMSE, MAE, SSIM");
  auto a = std::make_shared<std::string>();
  auto b = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("A", *a, "image to measure")->required();
  cmd->add_option("B", *b, "reference image")->required();
  cmd->add_flag("--json", *json, "print JSON");
  cmd->callback([=] {
    ImageDiff d = compareImages(readImage(*a), readImage(*b), *a, *b);
    if (*json) {
      nlohmann::json j = d.toJson();
      j["a"] = *a;
      j["b"] = *b;
      std::printf("%s\n", j.dump(2).c_str());
    } else {
      std::printf("rmse    %.6g\nrelmse  %.6g\nmae     %.6g\nssim    %.6f\n", d.rmse, d.relMse, d.mae, d.ssim);
    }
  });
}

}  // namespace vgi::app
