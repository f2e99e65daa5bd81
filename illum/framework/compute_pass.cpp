#include "illum/framework/compute_pass.h"

#include <glad/gl.h>

#include "core/error.h"
#include "illum/framework/sample_loop.h"
#include "shaders/shared/bindings.glsl"

namespace vgi {

UniformBuffer::UniformBuffer(size_t bytes) : bytes_(bytes) {
  glCreateBuffers(1, &buffer_);
  glNamedBufferStorage(buffer_, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
}

UniformBuffer::~UniformBuffer() { glDeleteBuffers(1, &buffer_); }

void UniformBuffer::upload(const void* data) const {
  glNamedBufferSubData(buffer_, 0, GLsizeiptr(bytes_), data);
}

void UniformBuffer::bind(unsigned unit) const { glBindBufferBase(GL_UNIFORM_BUFFER, unit, buffer_); }

void checkBlockLayout(unsigned program, const std::string& block, size_t bytes, const std::string& what) {
  const GLuint index = glGetProgramResourceIndex(program, GL_UNIFORM_BLOCK, block.c_str());
  if (index == GL_INVALID_INDEX) return;
  const GLenum prop = GL_BUFFER_DATA_SIZE;
  GLint size = 0;
  glGetProgramResourceiv(program, GL_UNIFORM_BLOCK, index, 1, &prop, 1, nullptr, &size);
  if (size_t(size) != bytes)
    fail("program (", what, "): uniform block '", block, "' is ", size,
         " bytes in std140 but its C++ struct is ", bytes,
         " (a params struct holds only 4-byte scalars and vec4s, padded to 16 bytes: "
         "illum/framework/compute_pass.h)");
}

const unsigned ComputePassBase::kImageAndFetchBarriers =
    GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT;

void gbufferInput(Frame& f, unsigned) { f.gbuffer().bind(); }

void ComputePassBase::create(Frame& f, const std::vector<std::string>& files, const ShaderDefines& defines,
                             std::vector<PassInput> inputs, size_t paramBytes) {
  program_ = f.shaders().program(files, defines);
  inputs_ = std::move(inputs);
  files_.clear();
  for (const std::string& file : files) files_ += (files_.empty() ? "" : ", ") + file;
  checkBlockLayout(program_, "Pass", paramBytes, files_);
}

void ComputePassBase::begin(Frame& f, const UniformBuffer& params) const {
  glUseProgram(program_);
  params.bind(UBO_PASS);
  for (PassInput bind : inputs_) bind(f, program_);
}

void ComputePassBase::dispatch(int width, int height, unsigned barriers) const {
  glDispatchCompute(unsigned(width + 7) / 8, unsigned(height + 7) / 8, 1);
  glMemoryBarrier(barriers);
}

}  // namespace vgi
