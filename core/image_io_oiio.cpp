// image_io through OpenImageIO (the full build).
#include <OpenImageIO/imageio.h>

#include <algorithm>

#include "core/error.h"
#include "core/image_io.h"

namespace vgi::image_io::oiio {

Pixels read(const std::string& path, const std::string& what) {
  using namespace OIIO;
  // A texture's colour is its RGB as stored: alpha (a cut-out mask, if anything) is not multiplied in
  // (OpenImageIO's default would premultiply it; the lean reader, like this, does not).
  ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = ImageInput::open(path, &config);
  if (!in) fail("cannot read ", what, " '", path, "': ", OIIO::geterror());
  const ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) fail(what, " '", path, "' has no pixels");
  if (size_t(spec.width) * size_t(spec.height) > kMaxPixels)
    fail(what, " '", path, "' is too large (", spec.width, "x", spec.height, ")");
  Pixels p;
  p.width = spec.width;
  p.height = spec.height;
  p.channels = std::min(spec.nchannels, 3);  // a header may claim a thousand
  p.srgb = spec.format.basetype == TypeDesc::UINT8 || spec.format.basetype == TypeDesc::UINT16;
  p.values.resize(size_t(p.width) * size_t(p.height) * size_t(p.channels));
  if (!in->read_image(0, 0, 0, p.channels, TypeDesc::FLOAT, p.values.data()))
    fail("cannot decode ", what, " '", path, "': ", in->geterror());
  // The display ("full") window; formats without one have it equal to the data window.
  const long fw = spec.full_width > 0 ? spec.full_width : spec.width,
             fh = spec.full_height > 0 ? spec.full_height : spec.height;
  if (size_t(fw) * size_t(fh) > kMaxPixels)
    fail(what, " '", path, "' is too large (display window ", fw, "x", fh, ")");
  return inDisplayWindow(std::move(p), spec.x, spec.y, spec.full_width > 0 ? spec.full_x : spec.x,
                         spec.full_height > 0 ? spec.full_y : spec.y, fw, fh);
}

namespace {
template <typename T>
void write(const std::string& path, int w, int h, const T* rgb, OIIO::TypeDesc type, bool zip) {
  using namespace OIIO;
  auto out = ImageOutput::create(path);
  if (!out) fail("cannot write '", path, "': ", OIIO::geterror());
  ImageSpec spec(w, h, 3, type);
  if (zip) spec.attribute("compression", "zip");
  if (!out->open(path, spec) || !out->write_image(type, rgb) || !out->close())
    fail("cannot write '", path, "': ", out->geterror());
}
}  // namespace

void writeExr(const std::string& path, int w, int h, const float* rgb) {
  write(path, w, h, rgb, OIIO::TypeDesc::FLOAT, true);
}

void writePng(const std::string& path, int w, int h, const unsigned char* rgb) {
  write(path, w, h, rgb, OIIO::TypeDesc::UINT8, false);
}

}  // namespace vgi::image_io::oiio
