#include "core/gpu_memory.h"

#include <glad/gl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/json_text.h"

namespace vgi {

namespace {
constexpr GLenum kGpuMemoryInfoTotalAvailableNvx = 0x9048;  // GL_NVX_gpu_memory_info, KiB
constexpr GLenum kGpuMemoryInfoCurrentAvailableNvx = 0x9049;
constexpr GLenum kTextureFreeMemoryAti = 0x87FC;  // GL_ATI_meminfo: 4 KiB values, [0] = total free

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

nlohmann::json measuredMemory(bool gl) {
  nlohmann::json m;
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  m["peak_rss_bytes"] = double(usage.ru_maxrss) * 1024.0;  // Linux: KiB
  std::ifstream statm("/proc/self/statm");
  double pages = 0, resident = 0;
  if (statm >> pages >> resident) m["rss_bytes"] = resident * double(sysconf(_SC_PAGE_SIZE));
  if (gl && hasExtension("GL_NVX_gpu_memory_info")) {
    GLint total = 0, available = 0;
    glGetIntegerv(kGpuMemoryInfoTotalAvailableNvx, &total);
    glGetIntegerv(kGpuMemoryInfoCurrentAvailableNvx, &available);
    m["gpu_total_bytes"] = double(total) * 1024.0;
    m["gpu_used_bytes"] = double(total - available) * 1024.0;  // by every process on the device
    m["gpu_report"] = "GL_NVX_gpu_memory_info";
  } else if (gl && hasExtension("GL_ATI_meminfo")) {
    GLint free[4] = {0, 0, 0, 0};
    glGetIntegerv(kTextureFreeMemoryAti, free);
    m["gpu_free_texture_bytes"] = double(free[0]) * 1024.0;
    m["gpu_report"] = "GL_ATI_meminfo";
  }
  return m;
}

nlohmann::json memoryAgainstResources(nlohmann::json now, const nlohmann::json& baseline,
                                      double resourcesBytes, double methodBytes, double targetsBytes) {
  now["baseline"] = baseline;
  now["resources_bytes"] = resourcesBytes;
  now["method_bytes"] = methodBytes;
  now["targets_bytes"] = targetsBytes;
  const double reported = resourcesBytes + methodBytes + targetsBytes;
  now["reported_bytes"] = reported;
  const char* key =
      now.contains("gpu_used_bytes") && baseline.contains("gpu_used_bytes") ? "gpu_used_bytes" : "rss_bytes";
  if (now.contains(key) && baseline.contains(key)) {
    const double growth = now[key].get<double>() - baseline[key].get<double>();
    now["growth_of"] = key;
    now["growth_bytes"] = growth;
    // A method that reports no bytes has no ratio: "undefined" (core/json_text.h), not null.
    now["growth_over_reported"] =
        reported > 0 ? finiteOrUndefined(growth / reported) : nlohmann::json(kUndefined);
  }
  return now;
}

}  // namespace vgi
