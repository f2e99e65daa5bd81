// The build's image_io: OpenImageIO, or the lean one with -DVGI_LEAN_IMAGES=ON.
#include "core/image_io.h"

namespace vgi::image_io {

#ifdef VGI_LEAN_IMAGES
namespace impl = lean;
const char* backend() { return "OpenEXR + libpng + libjpeg + stb_image"; }
#else
namespace impl = oiio;
const char* backend() { return "OpenImageIO"; }
#endif

Pixels read(const std::string& path, const std::string& what) { return impl::read(path, what); }
void writeExr(const std::string& path, int w, int h, const float* rgb) { impl::writeExr(path, w, h, rgb); }
void writePng(const std::string& path, int w, int h, const unsigned char* rgb) {
  impl::writePng(path, w, h, rgb);
}

}  // namespace vgi::image_io
