// Large GL allocations are estimated before they are made and refused, naming
// what asked for them, against a budget this GL and machine can state — not
// left to fail in the driver ("out of memory", an incomplete framebuffer).
#pragma once
#include <nlohmann/json_fwd.hpp>
#include <string>

namespace vgi {

// Bytes one run may allocate on the GL device: the dedicated memory the
// driver reports (GL_NVX_gpu_memory_info), else half of this machine's
// memory (llvmpipe keeps textures in system memory; a driver that reports
// nothing gets the same conservative cap). Needs a current GL context.
double gpuMemoryBudget();
// Throws naming `what` (the parameter and value that asked), `bytes` and the
// budget when the allocation exceeds it.
void checkGpuAllocation(double bytes, const std::string& what);
// The same for one shader storage buffer, which must also fit GL_MAX_SHADER_STORAGE_BLOCK_SIZE.
void checkSsboAllocation(double bytes, const std::string& what);

// What the process measurably uses, against which the resources' own byte counts can be read:
// resident and peak resident memory (where llvmpipe keeps every GL object), and with `gl` (a
// current context) the device's own report where the driver gives one — GL_NVX_gpu_memory_info
// (NVIDIA: total and available dedicated memory) or GL_ATI_meminfo (free texture memory).
nlohmann::json measuredMemory(bool gl);

// `now` (a measuredMemory) with `baseline` (the same, measured before the resources were built),
// the bytes the resources report and those the method keeps itself ("method_bytes": its state
// across frames, RenderResult::extra's "state_bytes"); "reported_bytes" is their sum. "growth_bytes"
// is how much the device's memory grew since the baseline — "gpu_used_bytes" where the driver
// reports it (growth_of says which), else "rss_bytes" (llvmpipe keeps GL objects in the process) —
// and "growth_over_reported" that growth over the reported bytes (1: the stats say what the render
// costs; a driver's copies, padding, or lazily committed pages move it either way;
// "undefined" without reported bytes).
// "targets_bytes" (the sample loop's G-buffer, film and scratch textures) counts in the reported bytes too.
nlohmann::json memoryAgainstResources(nlohmann::json now, const nlohmann::json& baseline,
                                      double resourcesBytes, double methodBytes = 0, double targetsBytes = 0);

}  // namespace vgi
