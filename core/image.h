// Linear HDR RGB images; EXR (float) and tone-mapped sRGB PNG (core/image_io.h: OpenImageIO, or
// OpenEXR + libpng + stb_image in the lean build).
#pragma once
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace vgi {

struct Image {
  int width = 0, height = 0;
  std::vector<glm::vec3> pixels;  // row 0 = top
  Image() = default;
  Image(int w, int h) : width(w), height(h), pixels(size_t(w) * h, glm::vec3(0.0f)) {}
  glm::vec3& at(int x, int y) { return pixels[size_t(y) * width + x]; }
  const glm::vec3& at(int x, int y) const { return pixels[size_t(y) * width + x]; }
};

// Writes by extension: .exr (float, linear), .png (exposure·x, clamp, sRGB).
void writeImage(const Image& img, const std::string& path, float exposure = 1.0f);
// Reads EXR, PNG, JPEG, HDR, TGA, BMP, …; 8/16-bit files are linearised from sRGB (then
// *displayEncoded, where given, is set: the file held display values in [0, 1], not linear HDR ones).
Image readImage(const std::string& path, bool* displayEncoded = nullptr);

float linearToSrgb(float x);
float srgbToLinear(float x);
float luminance(glm::vec3 c);

}  // namespace vgi
