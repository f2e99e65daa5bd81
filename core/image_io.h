// The image files the framework reads and writes, behind one small interface
// with two builds: OpenImageIO (the full build) or, with -DVGI_LEAN_IMAGES=ON,
// OpenEXR for EXR, libpng for writing PNG and stb_image for reading the other
// formats (the relocatable bundle's: a small fraction of OpenImageIO's run-time
// closure). Both give the same pixels: tests/core/image_io_test.cpp reads and
// writes through both and compares them bit for bit.
#pragma once
#include <string>
#include <vector>

namespace vgi::image_io {

// The first min(3, channels) channels of an image, interleaved, as float.
// srgb: the file stores 8- or 16-bit values (then in [0, 1], sRGB-encoded).
struct Pixels {
  int width = 0, height = 0, channels = 0;
  bool srgb = false;
  std::vector<float> values;
};

// The largest image read (pixels): a header may claim anything.
constexpr size_t kMaxPixels = size_t(1) << 28;

// An image's pixels are those of its display window (OpenEXR's; OpenImageIO's "full" window): a file
// whose data window is offset from it, smaller or larger (an EXR cropped to what is not black) is
// placed there, 0 where it has no data and clipped where it has data outside. `data` holds the data
// window's pixels, dataW x dataH at (dataX, dataY); the display window is fullW x fullH at (fullX, fullY).
inline Pixels inDisplayWindow(Pixels data, long dataX, long dataY, long fullX, long fullY, long fullW,
                              long fullH) {
  if (dataX == fullX && dataY == fullY && data.width == fullW && data.height == fullH) return data;
  Pixels p;
  p.width = int(fullW);
  p.height = int(fullH);
  p.channels = data.channels;
  p.srgb = data.srgb;
  p.values.assign(size_t(fullW) * size_t(fullH) * size_t(p.channels), 0.0f);
  const size_t c = size_t(p.channels);
  for (long y = 0; y < data.height; ++y) {
    const long fy = dataY + y - fullY;
    if (fy < 0 || fy >= fullH) continue;
    for (long x = 0; x < data.width; ++x) {
      const long fx = dataX + x - fullX;
      if (fx < 0 || fx >= fullW) continue;
      for (size_t k = 0; k < c; ++k)
        p.values[(size_t(fy) * size_t(fullW) + size_t(fx)) * c + k] =
            data.values[(size_t(y) * size_t(data.width) + size_t(x)) * c + k];
    }
  }
  return p;
}

// Each throws vgi::Error naming `what` (or the path) and the problem.
Pixels read(const std::string& path, const std::string& what);
void writeExr(const std::string& path, int width, int height, const float* rgb);          // float RGB, zip
void writePng(const std::string& path, int width, int height, const unsigned char* rgb);  // 8-bit RGB
const char* backend();

// The two implementations, by name (the build links one as the above; the tests compare both).
namespace oiio {
Pixels read(const std::string& path, const std::string& what);
void writeExr(const std::string& path, int width, int height, const float* rgb);
void writePng(const std::string& path, int width, int height, const unsigned char* rgb);
}  // namespace oiio
namespace lean {
Pixels read(const std::string& path, const std::string& what);
void writeExr(const std::string& path, int width, int height, const float* rgb);
void writePng(const std::string& path, int width, int height, const unsigned char* rgb);
}  // namespace lean

}  // namespace vgi::image_io
