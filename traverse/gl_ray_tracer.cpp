// GPU side of the tracers: uploads the pyramid and runs batches of rays through
// shaders/traverse/trace_rays.comp.glsl, which compiles the same shared kernels
// as traverse/ray_tracers.cpp.
#include "traverse/gl_ray_tracer.h"

#include <glad/gl.h>

#include "core/error.h"
#include "core/profiler.h"
#include "traverse/or_mip_pyramid.h"
#include "voxelize/gpu_grid.h"

namespace vgi {

GlPyramid::GlPyramid(const OrMipPyramid& pyramid, float marchStep)
    : box_(pyramid.box()), params_(pyramidParams(pyramid)) {
  marchStep_ = marchStep > 0.0f ? marchStep : defaultMarchStep(pyramid);
  glCreateBuffers(1, &buffer_);
  glNamedBufferStorage(buffer_, GLsizeiptr(pyramid.words().size() * 4), pyramid.words().data(), 0);
}

GlPyramid::~GlPyramid() {
  if (buffer_) glDeleteBuffers(1, &buffer_);
}

void GlPyramid::bind(unsigned program) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_PYRAMID, buffer_);
  setGridUniforms(program, box_);
  glUniform1ui(glGetUniformLocation(program, "uPyramidLevels"), params_.levels);
  glUniform1uiv(glGetUniformLocation(program, "uPyramidOffsets"), 16, params_.levelOffsets);
  glUniform1f(glGetUniformLocation(program, "uMarchStep"), marchStep_);
}

void addTracerDefine(ShaderDefines& defines, const std::string& tracer) {
  const TracerInfo& info = findTracer(tracer);
  if (!info.glsl) fail("tracer '", tracer, "' has no GLSL version (GLSL tracers: hierarchical, dda, march)");
  defines["VGI_TRACER"] = std::to_string(info.define);
}

std::vector<TraceResult> traceRaysGl(const GlPyramid& pyramid, ShaderLibrary& shaders, const std::string& tracer,
                                     const std::vector<TraceRay>& rays, Profiler& profiler) {
  ShaderDefines defines;
  addTracerDefine(defines, tracer);
  unsigned prog = shaders.program({"traverse/trace_rays.comp.glsl"}, defines);
  std::vector<TraceResult> out(rays.size());
  if (rays.empty()) return out;
  // Batches keep one dispatch short (llvmpipe has no preemption; drivers have watchdogs).
  const size_t batch = 1u << 18;
  unsigned bufs[2];
  glCreateBuffers(2, bufs);
  glNamedBufferStorage(bufs[0], GLsizeiptr(std::min(batch, rays.size()) * sizeof(TraceRay)), nullptr,
                       GL_DYNAMIC_STORAGE_BIT);
  glNamedBufferStorage(bufs[1], GLsizeiptr(std::min(batch, rays.size()) * 32), nullptr, 0);
  glUseProgram(prog);
  pyramid.bind(prog);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, bufs[0]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, bufs[1]);
  std::vector<glm::uvec4> hits;
  for (size_t b = 0; b < rays.size(); b += batch) {
    const size_t n = std::min(batch, rays.size() - b);
    glNamedBufferSubData(bufs[0], 0, GLsizeiptr(n * sizeof(TraceRay)), rays.data() + b);
    {
      auto s = profiler.scope("trace_" + tracer);
      glUniform1ui(glGetUniformLocation(prog, "uRayCount"), uint32_t(n));
      glDispatchCompute(uint32_t((n + 63) / 64), 1, 1);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    }
    hits.resize(2 * n);
    glGetNamedBufferSubData(bufs[1], 0, GLsizeiptr(n * 32), hits.data());
    for (size_t i = 0; i < n; ++i) {
      TraceResult& r = out[b + i];
      r.hit = hits[2 * i].x != 0u;
      r.t = glm::uintBitsToFloat(hits[2 * i].y);
      r.steps = hits[2 * i].z;
      r.voxel = glm::uvec3(hits[2 * i + 1]);
    }
  }
  glDeleteBuffers(2, bufs);
  return out;
}

}  // namespace vgi
