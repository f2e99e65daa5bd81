// The image layer's two builds (core/image_io.h) give the same pixels: files
// OpenImageIO writes in every format a scene uses (PNG 8/16-bit, grey and
// alpha, JPEG, TGA, HDR, EXR float / half / one channel / offset data window)
// are read bit for bit alike by OpenImageIO and by the lean reader, and each
// writer's EXR and PNG read back the same through both.
#include "core/image_io.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/error.h"
#include "test_util.h"

namespace vgi {
namespace {

namespace io = image_io;

std::string tmpDir(const std::string& name) { return testing::TempDir() + "/" + name; }

std::vector<float> ramp(int w, int h, int channels, float scale) {
  std::vector<float> v(size_t(w) * size_t(h) * size_t(channels));
  for (size_t i = 0; i < v.size(); ++i) v[i] = scale * float((i * 7919u) % 1000u) / 999.0f;
  return v;
}

// Writes `values` (float, `channels` per pixel) as `type` through OpenImageIO.
void writeWithOiio(const std::string& path, int w, int h, int channels, OIIO::TypeDesc type,
                   const std::vector<float>& values, int xOrigin = 0, int yOrigin = 0) {
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out) << path;
  OIIO::ImageSpec spec(w, h, channels, type);
  spec.x = xOrigin;
  spec.y = yOrigin;
  ASSERT_TRUE(out->open(path, spec)) << out->geterror();
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, values.data())) << out->geterror();
  ASSERT_TRUE(out->close());
}

void expectSameBits(const io::Pixels& a, const io::Pixels& b, const std::string& what) {
  ASSERT_EQ(a.width, b.width) << what;
  ASSERT_EQ(a.height, b.height) << what;
  ASSERT_EQ(a.channels, b.channels) << what;
  EXPECT_EQ(a.srgb, b.srgb) << what;
  ASSERT_EQ(a.values.size(), b.values.size()) << what;
  EXPECT_EQ(std::memcmp(a.values.data(), b.values.data(), a.values.size() * sizeof(float)), 0)
      << what << ": the two readers differ";
}

TEST(ImageIo, BothReadersGiveTheSamePixelsForEveryFormat) {
  const std::string dir = tmpDir("image_io");
  std::filesystem::create_directories(dir);
  struct Case {
    const char* name;
    int channels;
    OIIO::TypeDesc type;
    float scale;
    int x0, y0;
  };
  const Case cases[] = {
      {"rgb8.png", 3, OIIO::TypeDesc::UINT8, 1.0f, 0, 0},
      {"grey8.png", 1, OIIO::TypeDesc::UINT8, 1.0f, 0, 0},
      {"rgba8.png", 4, OIIO::TypeDesc::UINT8, 1.0f, 0, 0},
      {"rgb16.png", 3, OIIO::TypeDesc::UINT16, 1.0f, 0, 0},
      {"rgb.jpg", 3, OIIO::TypeDesc::UINT8, 1.0f, 0, 0},
      {"rgb.tga", 3, OIIO::TypeDesc::UINT8, 1.0f, 0, 0},
      {"rgb.hdr", 3, OIIO::TypeDesc::FLOAT, 40.0f, 0, 0},
      {"rgb.exr", 3, OIIO::TypeDesc::FLOAT, 40.0f, 0, 0},
      {"rgba_half.exr", 4, OIIO::TypeDesc::HALF, 8.0f, 0, 0},
      {"y.exr", 1, OIIO::TypeDesc::FLOAT, 3.0f, 0, 0},
      {"window.exr", 3, OIIO::TypeDesc::FLOAT, 2.0f, 5, -3},
  };
  for (const Case& c : cases) {
    const std::string path = dir + "/" + c.name;
    writeWithOiio(path, 37, 23, c.channels, c.type, ramp(37, 23, c.channels, c.scale), c.x0, c.y0);
    expectSameBits(io::oiio::read(path, "image"), io::lean::read(path, "image"), c.name);
  }
}

// An EXR's pixels are its display window's: a data window offset from it (4 rows down, from x = −4),
// inside it or around it is placed where it lies, 0 outside it (OpenEXR's definition), clipped
// beyond it — through both readers (they once read the data window as if it started at (0, 0)).
TEST(ImageIo, ExrPixelsAreReadInTheDisplayWindow) {
  const std::string dir = tmpDir("image_io_windows");
  std::filesystem::create_directories(dir);
  const int fullW = 8, fullH = 6;
  struct Case {
    const char* name;
    int x0, y0, w, h;  // the data window
  };
  const Case cases[] = {{"rows_down.exr", 0, 4, 8, 6},  {"x_from_minus4.exr", -4, 0, 8, 6},
                        {"inside.exr", 2, 1, 3, 2},     {"around.exr", -2, -1, 12, 9},
                        {"disjoint.exr", 20, 20, 4, 4}, {"same.exr", 0, 0, 8, 6}};
  for (const Case& c : cases) {
    const std::string path = dir + "/" + c.name;
    const std::vector<float> values = ramp(c.w, c.h, 3, 2.0f);
    {
      auto out = OIIO::ImageOutput::create(path);
      ASSERT_TRUE(out) << path;
      OIIO::ImageSpec spec(c.w, c.h, 3, OIIO::TypeDesc::FLOAT);
      spec.x = c.x0;
      spec.y = c.y0;
      spec.full_x = 0;
      spec.full_y = 0;
      spec.full_width = fullW;
      spec.full_height = fullH;
      ASSERT_TRUE(out->open(path, spec)) << out->geterror();
      ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, values.data())) << out->geterror();
      ASSERT_TRUE(out->close());
    }
    for (const io::Pixels& p : {io::oiio::read(path, "image"), io::lean::read(path, "image")}) {
      ASSERT_EQ(p.width, fullW) << c.name;
      ASSERT_EQ(p.height, fullH) << c.name;
      ASSERT_EQ(p.channels, 3) << c.name;
      for (int y = 0; y < fullH; ++y)
        for (int x = 0; x < fullW; ++x)
          for (int k = 0; k < 3; ++k) {
            const int dx = x - c.x0, dy = y - c.y0;
            const bool inData = dx >= 0 && dx < c.w && dy >= 0 && dy < c.h;
            const float want =
                inData ? values[(size_t(dy) * size_t(c.w) + size_t(dx)) * 3 + size_t(k)] : 0.0f;
            ASSERT_EQ(p.values[(size_t(y) * fullW + size_t(x)) * 3 + size_t(k)], want)
                << c.name << " pixel (" << x << ", " << y << ") channel " << k;
          }
    }
  }
}

TEST(ImageIo, EachWritersFilesReadBackTheSameThroughBoth) {
  const std::string dir = tmpDir("image_io_write");
  std::filesystem::create_directories(dir);
  const int w = 41, h = 19;
  const std::vector<float> rgb = ramp(w, h, 3, 25.0f);
  std::vector<unsigned char> bytes(rgb.size());
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = (unsigned char)((i * 31u) % 256u);
  io::oiio::writeExr(dir + "/oiio.exr", w, h, rgb.data());
  io::lean::writeExr(dir + "/lean.exr", w, h, rgb.data());
  io::oiio::writePng(dir + "/oiio.png", w, h, bytes.data());
  io::lean::writePng(dir + "/lean.png", w, h, bytes.data());
  for (const char* f : {"oiio.exr", "lean.exr"}) {
    const io::Pixels a = io::oiio::read(dir + "/" + f, "image"), b = io::lean::read(dir + "/" + f, "image");
    expectSameBits(a, b, f);
    EXPECT_EQ(std::memcmp(a.values.data(), rgb.data(), rgb.size() * sizeof(float)), 0) << f << ": lossless";
  }
  for (const char* f : {"oiio.png", "lean.png"}) {
    const io::Pixels a = io::oiio::read(dir + "/" + f, "image"), b = io::lean::read(dir + "/" + f, "image");
    expectSameBits(a, b, f);
    for (size_t i = 0; i < bytes.size(); ++i)
      ASSERT_EQ(std::lround(a.values[i] * 255.0f), bytes[i]) << f << " value " << i;
  }
}

TEST(ImageIo, TheLeanReaderRefusesWhatItCannotRead) {
  const std::string dir = tmpDir("image_io_bad");
  std::filesystem::create_directories(dir);
  const std::string text = dir + "/not_an_image.png";
  std::ofstream(text) << "hello";
  test::expectError([&] { io::lean::read(text, "texture"); }, {"texture", "not_an_image.png"});
  const std::string truncated = dir + "/truncated.exr";
  writeWithOiio(truncated, 64, 64, 3, OIIO::TypeDesc::FLOAT, ramp(64, 64, 3, 1.0f));
  std::filesystem::resize_file(truncated, 400);
  test::expectError([&] { io::lean::read(truncated, "texture"); }, {"texture", "truncated.exr"});
}

}  // namespace
}  // namespace vgi
