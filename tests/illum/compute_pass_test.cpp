// Typed passes (illum/framework/compute_pass.h): a params struct of the
// allowed member kinds reaches the shader with every member at its C++ place,
// and a struct that breaks the layout rule is refused by name.
#include "illum/framework/compute_pass.h"

#include <glad/gl.h>
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "core/error.h"
#include "core/gl_context.h"
#include "core/shader_library.h"
#include "shaders/shared/bindings.glsl"
#include "tests/data/shaders/pass_params_probe.glsl"

namespace vgi {
namespace {

using shared::MisalignedParams;
using shared::ProbeParams;

TEST(ComputePass, ParamsReachTheShaderAtTheirCppPlaces) {
  auto ctx = GlContext::create();
  ShaderLibrary shaders;
  const unsigned prog = shaders.program({"../tests/data/shaders/pass_params_probe.comp.glsl"});
  EXPECT_NO_THROW(checkBlockLayout(prog, "Pass", sizeof(ProbeParams), "probe"));
  // Every 4-byte word a distinct bit pattern; the shader returns the members in order, which for a
  // struct of the allowed kinds is the C++ struct's words in order.
  UniformBlock<ProbeParams> block;
  const size_t words = sizeof(ProbeParams) / 4;
  std::vector<uint32_t> pattern(words);
  for (size_t i = 0; i < words; ++i) pattern[i] = 0x3f800000u + uint32_t(i) * 977u;  // finite floats
  std::memcpy(static_cast<void*>(&block.value), pattern.data(), sizeof(ProbeParams));
  block.upload();
  unsigned buf = 0;
  glCreateBuffers(1, &buf);
  glNamedBufferStorage(buf, GLsizeiptr(sizeof(ProbeParams)), nullptr, 0);
  glUseProgram(prog);
  block.buffer().bind(UBO_PASS);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_TRACE_HITS, buf);
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<uint32_t> gpu(words);
  glGetNamedBufferSubData(buf, 0, GLsizeiptr(sizeof(ProbeParams)), gpu.data());
  glDeleteBuffers(1, &buf);
  EXPECT_EQ(gpu, pattern);
  EXPECT_EQ(ctx->errorCount(), 0);
}

TEST(ComputePass, AStructThatBreaksTheLayoutRuleIsRefusedWithBothSizes) {
  auto ctx = GlContext::create();
  ShaderLibrary shaders;
  const unsigned prog =
      shaders.program({"../tests/data/shaders/pass_params_probe.comp.glsl"}, {{"MISALIGNED", "1"}});
  static_assert(sizeof(MisalignedParams) == 32, "C++ packs the vec4 after the float");
  try {
    checkBlockLayout(prog, "Pass", sizeof(MisalignedParams), "probe");
    FAIL() << "a vec4 after a lone float passed the layout check";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("'Pass' is 48 bytes in std140 but its C++ struct is 32"), std::string::npos) << m;
  }
  // A block the program does not declare is no error (the pass may not use it).
  EXPECT_NO_THROW(checkBlockLayout(prog, "NoSuchBlock", 16, "probe"));
}

}  // namespace
}  // namespace vgi
