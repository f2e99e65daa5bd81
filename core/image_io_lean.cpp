// image_io without OpenImageIO (-DVGI_LEAN_IMAGES=ON, the relocatable bundle):
// OpenEXR reads and writes EXR, libpng writes PNG, libjpeg reads JPEG and
// stb_image the other formats (PNG, TGA, BMP, HDR, …). The pixels equal OpenImageIO's
// (tests/core/image_io_test.cpp).
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <jpeglib.h>
#include <png.h>
#include <stb/stb_image.h>

#include <algorithm>
#include <csetjmp>
#include <cstdio>
#include <fstream>
#include <memory>

#include "core/error.h"
#include "core/image_io.h"

namespace vgi::image_io::lean {

namespace {

bool isExr(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char magic[4] = {0, 0, 0, 0};
  in.read(reinterpret_cast<char*>(magic), 4);
  return in && magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 && magic[3] == 0x01;
}

Pixels readExr(const std::string& path, const std::string& what) {
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const Imath::Box2i dw = header.dataWindow();
    const long w = long(dw.max.x) - dw.min.x + 1, h = long(dw.max.y) - dw.min.y + 1;
    if (w <= 0 || h <= 0) fail(what, " '", path, "' has no pixels");
    if (size_t(w) * size_t(h) > kMaxPixels) fail(what, " '", path, "' is too large (", w, "x", h, ")");
    // R, G, B when present (as OpenImageIO orders them), else the first channels by name.
    std::vector<std::string> names;
    const Imf::ChannelList& list = header.channels();
    if (list.findChannel("R") && list.findChannel("G") && list.findChannel("B")) {
      names = {"R", "G", "B"};
    } else {
      for (auto it = list.begin(); it != list.end() && names.size() < 3; ++it) names.push_back(it.name());
    }
    if (names.empty()) fail(what, " '", path, "' has no channels");
    Pixels p;
    p.width = int(w);
    p.height = int(h);
    p.channels = int(names.size());
    p.values.resize(size_t(w) * size_t(h) * names.size());
    Imf::FrameBuffer fb;
    const size_t xs = sizeof(float) * names.size(), ys = xs * size_t(w);
    // The slices' base is addressed by the data window's coordinates.
    char* origin = reinterpret_cast<char*>(p.values.data()) - ptrdiff_t(dw.min.x) * ptrdiff_t(xs) -
                   ptrdiff_t(dw.min.y) * ptrdiff_t(ys);
    for (size_t c = 0; c < names.size(); ++c)
      fb.insert(names[c].c_str(), Imf::Slice(Imf::FLOAT, origin + c * sizeof(float), xs, ys));
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    const Imath::Box2i display = header.displayWindow();
    const long fw = long(display.max.x) - display.min.x + 1, fh = long(display.max.y) - display.min.y + 1;
    if (fw <= 0 || fh <= 0) fail(what, " '", path, "' has an empty display window");
    if (size_t(fw) * size_t(fh) > kMaxPixels)
      fail(what, " '", path, "' is too large (display window ", fw, "x", fh, ")");
    return inDisplayWindow(std::move(p), dw.min.x, dw.min.y, display.min.x, display.min.y, fw, fh);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    fail("cannot read ", what, " '", path, "': ", e.what());
  }
}

bool isJpeg(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char magic[3] = {0, 0, 0};
  in.read(reinterpret_cast<char*>(magic), 3);
  return in && magic[0] == 0xff && magic[1] == 0xd8 && magic[2] == 0xff;
}

// JPEG through libjpeg with its default decoding (as OpenImageIO decodes it: stb_image's own decoder
// rounds differently).
struct JpegError {
  jpeg_error_mgr mgr;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX] = {0};
};

Pixels readJpeg(const std::string& path, const std::string& what) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) fail("cannot read ", what, " '", path, "'");
  jpeg_decompress_struct info{};
  JpegError err;
  info.err = jpeg_std_error(&err.mgr);
  err.mgr.error_exit = [](j_common_ptr c) {
    JpegError* e = reinterpret_cast<JpegError*>(c->err);
    e->mgr.format_message(c, e->message);
    std::longjmp(e->jump, 1);
  };
  Pixels p;
  std::vector<unsigned char> row;
  // No C++ object with a destructor is created between setjmp and a longjmp back to it.
  if (setjmp(err.jump)) {
    jpeg_destroy_decompress(&info);
    fail("cannot decode ", what, " '", path, "': ", err.message);
  }
  jpeg_create_decompress(&info);
  jpeg_stdio_src(&info, file.get());
  jpeg_read_header(&info, TRUE);
  if (info.num_components != 1 && info.num_components != 3) info.out_color_space = JCS_RGB;
  jpeg_start_decompress(&info);
  const size_t w = info.output_width, h = info.output_height, comp = size_t(info.output_components);
  if (w == 0 || h == 0 || w * h > kMaxPixels) {
    jpeg_destroy_decompress(&info);
    fail(what, " '", path, "' has no pixels or is too large (", w, "x", h, ")");
  }
  p.width = int(w);
  p.height = int(h);
  p.channels = int(std::min<size_t>(comp, 3));
  p.srgb = true;
  p.values.resize(w * h * size_t(p.channels));
  row.resize(w * comp);
  while (info.output_scanline < info.output_height) {
    const size_t y = info.output_scanline;
    JSAMPROW r = row.data();
    jpeg_read_scanlines(&info, &r, 1);
    for (size_t x = 0; x < w; ++x)
      for (size_t c = 0; c < size_t(p.channels); ++c)
        p.values[(y * w + x) * size_t(p.channels) + c] = float(row[x * comp + c]) * (1.0f / 255.0f);
  }
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  return p;
}

Pixels readStb(const std::string& path, const std::string& what) {
  int w = 0, h = 0, comp = 0;
  if (!stbi_info(path.c_str(), &w, &h, &comp))
    fail("cannot read ", what, " '", path,
         "': ", stbi_failure_reason() ? stbi_failure_reason() : "unknown format");
  if (w <= 0 || h <= 0 || comp <= 0) fail(what, " '", path, "' has no pixels");
  if (size_t(w) * size_t(h) > kMaxPixels) fail(what, " '", path, "' is too large (", w, "x", h, ")");
  Pixels p;
  p.width = w;
  p.height = h;
  p.channels = std::min(comp, 3);
  p.values.resize(size_t(w) * size_t(h) * size_t(p.channels));
  auto take = [&](auto* data, float scale) {
    if (!data)
      fail("cannot decode ", what, " '", path, "': ", stbi_failure_reason() ? stbi_failure_reason() : "?");
    for (size_t i = 0; i < size_t(w) * size_t(h); ++i)
      for (int c = 0; c < p.channels; ++c)
        p.values[i * size_t(p.channels) + size_t(c)] = float(data[i * size_t(comp) + size_t(c)]) * scale;
    stbi_image_free(data);
  };
  if (stbi_is_hdr(path.c_str())) {
    take(stbi_loadf(path.c_str(), &w, &h, &comp, 0), 1.0f);
  } else if (stbi_is_16_bit(path.c_str())) {
    p.srgb = true;
    take(stbi_load_16(path.c_str(), &w, &h, &comp, 0), 1.0f / 65535.0f);
  } else {
    p.srgb = true;
    take(stbi_load(path.c_str(), &w, &h, &comp, 0), 1.0f / 255.0f);
  }
  return p;
}

}  // namespace

Pixels read(const std::string& path, const std::string& what) {
  if (isExr(path)) return readExr(path, what);
  if (isJpeg(path)) return readJpeg(path, what);
  return readStb(path, what);
}

void writeExr(const std::string& path, int w, int h, const float* rgb) {
  try {
    Imf::Header header(w, h);
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer fb;
    const size_t xs = 3 * sizeof(float), ys = xs * size_t(w);
    char* base = const_cast<char*>(reinterpret_cast<const char*>(rgb));
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
      header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
      fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + size_t(c) * sizeof(float), xs, ys));
    }
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(h);
  } catch (const std::exception& e) {
    fail("cannot write '", path, "': ", e.what());
  }
}

void writePng(const std::string& path, int w, int h, const unsigned char* rgb) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = png_uint_32(w);
  image.height = png_uint_32(h);
  image.format = PNG_FORMAT_RGB;
  if (!png_image_write_to_file(&image, path.c_str(), 0, rgb, 0, nullptr))
    fail("cannot write '", path, "': ", image.message);
}

}  // namespace vgi::image_io::lean
