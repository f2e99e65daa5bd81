#include "core/image.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "core/image_io.h"
#include "core/scene_loader.h"

namespace vgi {

float linearToSrgb(float x) {
  x = std::clamp(x, 0.0f, 1.0f);
  return x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
}

float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

float luminance(glm::vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

void writeImage(const Image& img, const std::string& path, float exposure) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (auto& c : ext) c = char(std::tolower(c));
  auto parent = std::filesystem::path(path).parent_path();
  if (!parent.empty() && !std::filesystem::exists(parent))
    fail("cannot write '", path, "': folder '", parent.string(), "' does not exist");
  if (ext == ".exr") {
    image_io::writeExr(path, img.width, img.height, &img.pixels[0].x);
  } else if (ext == ".png") {
    std::vector<unsigned char> px(img.pixels.size() * 3);
    for (size_t i = 0; i < img.pixels.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        float v = img.pixels[i][k] * exposure;
        if (!std::isfinite(v)) v = 0;  // NaN must never turn into a plausible colour
        px[i * 3 + k] = (unsigned char)std::lround(linearToSrgb(v) * 255.0f);
      }
    image_io::writePng(path, img.width, img.height, px.data());
  } else {
    fail("cannot write '", path, "': unknown image format '", ext, "' (.exr or .png)");
  }
}

Image readImage(const std::string& path, bool* displayEncoded) {
  Texture t = loadTexture(path, "image");
  if (displayEncoded) *displayEncoded = t.srgb;
  // An image read to be measured (diff, compare --reference, a sweep's reference file): a metric over
  // pixels that are not numbers would mean nothing, and reading them as 0 would hide them.
  if (t.nonFiniteTexels > 0)
    fail("image '", path, "' has ", t.nonFiniteTexels, " non-finite (NaN or Inf) channel value(s) in ",
         t.width, "x", t.height, " pixels: refused (an error metric over them means nothing)");
  Image img(t.width, t.height);
  img.pixels = std::move(t.texels);
  return img;
}

}  // namespace vgi
