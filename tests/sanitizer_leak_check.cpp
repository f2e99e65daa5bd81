// The sanitizer suite's check on its own suppressions (scripts/lsan.supp): a process that makes a GL
// context on a driver (--gl egl: llvmpipe, --gl zink: zink on lavapipe), compiles and runs a compute
// program, and exits must pass LeakSanitizer — the drivers' leaks at exit are suppressed — while the
// same process with --leak, which loses memory in the project's own code, must fail it, naming
// deliberateLeak. Built and run only in an AddressSanitizer build (tests/CMakeLists.txt).
#include <glad/gl.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "core/error.h"
#include "core/gl_context.h"

namespace {

// Loses three blocks: no pointer to them survives the call, so LeakSanitizer reports them with this
// function in their stacks (not inlined, so the frame keeps its name).
__attribute__((noinline)) void deliberateLeak() {
  for (int i = 0; i < 3; ++i) {
    void* volatile p = std::malloc(64 + size_t(i));
    std::memset(p, i, 64);
    p = nullptr;
  }
}

// What a render does to a driver, in small: a program compiled, a buffer written by a dispatch.
void runComputeProgram() {
  const char* src =
      "#version 450\nlayout(local_size_x = 64) in;\n"
      "layout(std430, binding = 0) buffer B { uint v[]; };\n"
      "void main() { v[gl_GlobalInvocationID.x] = gl_GlobalInvocationID.x * 3u; }\n";
  GLuint sh = glCreateShader(GL_COMPUTE_SHADER);
  glShaderSource(sh, 1, &src, nullptr);
  glCompileShader(sh);
  GLuint prog = glCreateProgram();
  glAttachShader(prog, sh);
  glLinkProgram(prog);
  GLint ok = 0;
  glGetProgramiv(prog, GL_LINK_STATUS, &ok);
  if (!ok) vgi::fail("the check's compute program did not link");
  GLuint buf = 0;
  glCreateBuffers(1, &buf);
  glNamedBufferStorage(buf, 256 * sizeof(GLuint), nullptr, GL_MAP_READ_BIT);
  glUseProgram(prog);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buf);
  glDispatchCompute(4, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  GLuint last = 0;
  glGetNamedBufferSubData(buf, 255 * sizeof(GLuint), sizeof(GLuint), &last);
  if (last != 255u * 3u) vgi::fail("the check's dispatch wrote ", last, ", not ", 255u * 3u);
  glDeleteBuffers(1, &buf);
  glDeleteProgram(prog);
  glDeleteShader(sh);
}

}  // namespace

int main(int argc, char** argv) {
  std::string backend = "egl";
  bool leak = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--leak") {
      leak = true;
    } else if (a == "--gl" && i + 1 < argc) {
      backend = argv[++i];
    } else {
      std::fprintf(stderr, "usage: %s [--gl egl|zink|osmesa] [--leak]\n", argv[0]);
      return 2;
    }
  }
  try {
    std::unique_ptr<vgi::GlContext> gl = vgi::GlContext::create(vgi::parseGlBackend(backend));
    runComputeProgram();
    std::printf("%s: %s\n", backend.c_str(), gl->renderer().c_str());
  } catch (const vgi::Error& e) {
    std::fprintf(stderr, "sanitizer_leak_check: %s\n", e.what());
    return 1;
  }
  if (leak) deliberateLeak();
  return 0;
}
