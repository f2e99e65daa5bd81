#include "core/gl_handles.h"

#include <glad/gl.h>

namespace vgi {

namespace detail {
void deleteGlTexture(unsigned name) { glDeleteTextures(1, &name); }
void deleteGlBuffer(unsigned name) { glDeleteBuffers(1, &name); }
}  // namespace detail

GlTexture makeTexture2D(int width, int height, unsigned internalFormat) {
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &t);
  GlTexture owned(t);
  glTextureStorage2D(t, 1, internalFormat, width, height);
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return owned;
}

GlBuffer makeBuffer(size_t bytes) {
  GLuint b = 0;
  glCreateBuffers(1, &b);
  GlBuffer owned(b);
  glNamedBufferStorage(b, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
  return owned;
}

}  // namespace vgi
