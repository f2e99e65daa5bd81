// Move-only owners of GL object names: the name is deleted with its owner,
// so a module that throws half-way leaks nothing and a class holding them
// needs no destructor. A default-constructed handle owns nothing (name 0).
#pragma once
#include <cstddef>
#include <utility>

namespace vgi {

namespace detail {
void deleteGlTexture(unsigned name);
void deleteGlBuffer(unsigned name);
}  // namespace detail

template <void (*Delete)(unsigned)>
class GlHandle {
 public:
  GlHandle() = default;
  explicit GlHandle(unsigned name) : name_(name) {}
  ~GlHandle() { reset(); }
  GlHandle(GlHandle&& o) noexcept : name_(std::exchange(o.name_, 0u)) {}
  GlHandle& operator=(GlHandle&& o) noexcept {
    if (this != &o) {
      reset();
      name_ = std::exchange(o.name_, 0u);
    }
    return *this;
  }
  GlHandle(const GlHandle&) = delete;
  GlHandle& operator=(const GlHandle&) = delete;
  unsigned get() const { return name_; }
  explicit operator bool() const { return name_ != 0; }
  void reset() {
    if (name_) Delete(name_);
    name_ = 0;
  }

 private:
  unsigned name_ = 0;
};

using GlTexture = GlHandle<detail::deleteGlTexture>;
using GlBuffer = GlHandle<detail::deleteGlBuffer>;

// A new 2D texture of one level (glTextureStorage2D), nearest filtering.
GlTexture makeTexture2D(int width, int height, unsigned internalFormat);
// A new buffer of `bytes` (glNamedBufferStorage, dynamic storage: updatable from the CPU).
GlBuffer makeBuffer(size_t bytes);

}  // namespace vgi
