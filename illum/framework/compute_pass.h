// Typed passes. A pass's parameters are one struct, declared once for C++ and
// GLSL in a params.glsl beside its shaders (the shared dialect of
// shaders/shared/cpp_prelude.h), filled by the method and uploaded as a std140
// uniform block; enumerations cross as named constants of the same file. No
// uniform name is spelled twice, no GLSL enum lives in a C++ ternary.
//
// Layout rule (checked): a params struct holds only 4-byte scalars (int, uint,
// float — never bool) and vec4 / ivec4 / uvec4 or arrays of them, and its size
// is a multiple of 16 (explicit pad fields). std140 can then only add padding
// to the C++ layout, so a block whose size GL reports equal to sizeof(T) has
// every member at the C++ offset: checkBlockLayout compares the two for every
// program that declares the block.
#pragma once
#include <cstddef>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/shader_library.h"

namespace vgi {

class Frame;

// A GL uniform buffer of a fixed size.
class UniformBuffer {
 public:
  explicit UniformBuffer(size_t bytes);
  ~UniformBuffer();
  UniformBuffer(const UniformBuffer&) = delete;
  UniformBuffer& operator=(const UniformBuffer&) = delete;
  void upload(const void* data) const;  // bytes() bytes
  void bind(unsigned unit) const;       // at GL_UNIFORM_BUFFER unit (shared/bindings.glsl's UBO_*)
  size_t bytes() const { return bytes_; }

 private:
  unsigned buffer_ = 0;
  size_t bytes_ = 0;
};

// Throws vgi::Error (naming `what`, the block and both sizes) unless the
// uniform block `block` of `program` is `bytes` long; a program that does not
// declare the block (or whose compiler dropped it) passes.
void checkBlockLayout(unsigned program, const std::string& block, size_t bytes, const std::string& what);

// One params struct as a uniform block: `value` is uploaded by upload().
template <class T>
class UniformBlock {
  static_assert(sizeof(T) % 16 == 0, "a params struct is padded to a multiple of 16 bytes (std140)");
  static_assert(std::is_standard_layout<T>::value, "a params struct is plain data");

 public:
  T value{};
  void upload() {
    if (!buffer_) buffer_ = std::make_unique<UniformBuffer>(sizeof(T));
    buffer_->upload(&value);
  }
  const UniformBuffer& buffer() const { return *buffer_; }

 private:
  std::unique_ptr<UniformBuffer> buffer_;
};

// What a compute pass reads from the frame besides its parameters, each binding itself to the
// program: a resource's input is declared beside the resource (illum/resources/: gpuSceneInput,
// lightMapsInput, valueTexturesInput), the G-buffer's here. The framework knows the slots, not the kinds.
using PassInput = void (*)(Frame& f, unsigned program);
void gbufferInput(Frame& f, unsigned program);  // this sample's G-buffer

// A compute pass over an image: its program, its parameter block P (declared
// in GLSL as `layout(std140, binding = UBO_PASS) uniform Pass { P pass; };`), the
// frame inputs it declares, and the dispatch of 8×8 groups over W×H with the
// barrier after it. The method binds what only it has (a volume, a tracer,
// images) between use() and dispatch().
class ComputePassBase {
 public:
  unsigned program() const { return program_; }
  const std::string& files() const { return files_; }  // its shader files, for messages
  // glDispatchCompute over ceil(w/8) × ceil(h/8) groups, then `barriers`.
  void dispatch(int width, int height, unsigned barriers = kImageAndFetchBarriers) const;
  static const unsigned kImageAndFetchBarriers;

 protected:
  void create(Frame& f, const std::vector<std::string>& files, const ShaderDefines& defines,
              std::vector<PassInput> inputs, size_t paramBytes);
  // glUseProgram, `params` at UBO_PASS, the declared inputs.
  void begin(Frame& f, const UniformBuffer& params) const;

 private:
  unsigned program_ = 0;
  std::string files_;
  std::vector<PassInput> inputs_;
};

template <class P>
class ComputePass : public ComputePassBase {
 public:
  P& params() { return block_.value; }
  void create(Frame& f, const std::vector<std::string>& files, const ShaderDefines& defines,
              std::vector<PassInput> inputs) {
    ComputePassBase::create(f, files, defines, std::move(inputs), sizeof(P));
  }
  // Makes the program current, uploads and binds the parameters, binds the inputs.
  void use(Frame& f) {
    block_.upload();
    begin(f, block_.buffer());
  }

 private:
  UniformBlock<P> block_;
};

}  // namespace vgi
