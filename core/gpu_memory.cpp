#include "core/gpu_memory.h"

#include <glad/gl.h>
#include <unistd.h>

#include <cstring>

#include "core/error.h"

namespace vgi {

namespace {
constexpr GLenum kGpuMemoryInfoTotalAvailableNvx = 0x9048;  // GL_NVX_gpu_memory_info, KiB

bool hasExtension(const char* name) {
  GLint n = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &n);
  for (GLint i = 0; i < n; ++i) {
    const char* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
    if (e && std::strcmp(e, name) == 0) return true;
  }
  return false;
}

double mib(double bytes) { return bytes / double(1 << 20); }
}  // namespace

double gpuMemoryBudget() {
  if (hasExtension("GL_NVX_gpu_memory_info")) {
    GLint kib = 0;
    glGetIntegerv(kGpuMemoryInfoTotalAvailableNvx, &kib);
    if (kib > 0) return double(kib) * 1024.0;
  }
  return 0.5 * double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
}

void checkGpuAllocation(double bytes, const std::string& what) {
  const double budget = gpuMemoryBudget();
  if (bytes > budget)
    fail(what, " needs ", mib(bytes), " MiB of GL memory; this device allows ", mib(budget),
         " MiB (the driver's dedicated memory, or half of this machine's)");
}

void checkSsboAllocation(double bytes, const std::string& what) {
  GLint64 maxBlock = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
  if (maxBlock > 0 && bytes > double(maxBlock))
    fail(what, " needs a ", mib(bytes), " MiB storage buffer; this GL's largest is ", mib(double(maxBlock)),
         " MiB (GL_MAX_SHADER_STORAGE_BLOCK_SIZE)");
  checkGpuAllocation(bytes, what);
}

}  // namespace vgi
