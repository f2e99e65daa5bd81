// GPU side of the tracers: uploads the pyramid and runs batches of rays through
// shaders/traverse/trace_rays.comp.glsl, which compiles the same shared kernels
// as traverse/ray_tracers.cpp.
#include "traverse/gl_ray_tracer.h"

#include <glad/gl.h>

#include "core/error.h"
#include "core/params.h"
#include "core/profiler.h"
#include "shaders/shared/or_mip.glsl"
#include "traverse/gpu_bvh.h"
#include "traverse/or_mip_pyramid.h"
#include "voxelize/gpu_grid.h"

namespace vgi {

GlPyramid::GlPyramid(const OrMipPyramid& pyramid, float marchStep)
    : box_(pyramid.box()), params_(pyramidParams(pyramid)) {
  totalWords_ = uint32_t(pyramid.words().size());
  marchStep_ = marchStep > 0.0f ? marchStep : defaultMarchStep(pyramid);
  glCreateBuffers(1, &buffer_);
  glNamedBufferStorage(buffer_, GLsizeiptr(pyramid.words().size() * 4), pyramid.words().data(),
                       GL_DYNAMIC_STORAGE_BIT);
}

GlPyramid::GlPyramid(const GridBox& box, float marchStep) : box_(box), params_(pyramidParams(box)) {
  marchStep_ = marchStep > 0.0f ? marchStep : defaultMarchStep(box);
  OrMipPyramid::layout(box, totalWords_);
  glCreateBuffers(1, &buffer_);
  glNamedBufferStorage(buffer_, GLsizeiptr(size_t(totalWords_) * 4), nullptr, GL_DYNAMIC_STORAGE_BIT);
}

void GlPyramid::build(const GpuGridBuffer& grid, ShaderLibrary& shaders) {
  const size_t bytes = size_t(box_.resolution.x) * box_.resolution.y * (box_.resolution.z / 32u) * 4;
  if (grid.bytes() != bytes)
    fail("GlPyramid::build: grid of ", grid.bytes(), " bytes, the pyramid's level 0 has ", bytes);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  glCopyNamedBufferSubData(grid.buffer(), buffer_, 0, 0, GLsizeiptr(bytes));
  reduce(shaders);
}

void GlPyramid::build(const BinaryGrid& grid, ShaderLibrary& shaders) {
  if (!(grid.box().resolution == box_.resolution))
    fail("GlPyramid::build: the grid's resolution differs from the pyramid's");
  glNamedBufferSubData(buffer_, 0, GLsizeiptr(grid.words().size() * 4), grid.words().data());
  reduce(shaders);
}

void GlPyramid::reduce(ShaderLibrary& shaders) {
  const unsigned prog = shaders.program({"traverse/or_mip.comp.glsl"});
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_GRID_WORDS, buffer_);
  glUseProgram(prog);
  const glm::uvec2 base(box_.resolution.x, box_.resolution.y);
  const uint32_t D = box_.resolution.z, wpc = D / 32u;
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  for (uint32_t l = 1; l < params_.levels; ++l) {
    glm::uvec2 s = shared::mipLevelSize(base, l), c = shared::mipLevelSize(base, l - 1);
    shaders.setUniform(prog, "uSize", s);
    shaders.setUniform(prog, "uChildSize", c);
    shaders.setUniform(prog, "uDepth", D);
    shaders.setUniform(prog, "uOffset", params_.levelOffsets[l]);
    shaders.setUniform(prog, "uChildOffset", params_.levelOffsets[l - 1]);
    glDispatchCompute((s.x + 7u) / 8u, (s.y + 7u) / 8u, wpc);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  }
}

std::vector<uint32_t> GlPyramid::read() const {
  std::vector<uint32_t> words(totalWords_);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(buffer_, 0, GLsizeiptr(size_t(totalWords_) * 4), words.data());
  return words;
}

uint64_t GlPyramid::countLevel0() const {
  const uint32_t words = params_.levels > 1 ? params_.levelOffsets[1] : totalWords_;
  std::vector<uint32_t> w(words);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(buffer_, 0, GLsizeiptr(size_t(words) * 4), w.data());
  uint64_t n = 0;
  for (uint32_t x : w) n += uint64_t(__builtin_popcount(x));
  return n;
}

std::vector<uint32_t> buildOrMipGl(const BinaryGrid& grid, ShaderLibrary& shaders) {
  GlPyramid p(grid.box());
  p.build(grid, shaders);
  return p.read();
}

GlPyramid::~GlPyramid() {
  if (buffer_) glDeleteBuffers(1, &buffer_);
}

void GlPyramid::bind(ShaderLibrary& shaders, unsigned program) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_PYRAMID, buffer_);
  setGridUniforms(shaders, program, box_);
  shaders.setUniform(program, "uPyramidLevels", params_.levels);
  shaders.setUniformArray(program, "uPyramidOffsets", params_.levelOffsets, 16);
  shaders.setUniform(program, "uMarchStep", marchStep_);
}

std::string readTracerParam(ParamSet& p, bool triangles) {
  if (!triangles)
    return p.getString("tracer", "hierarchical", "voxel tracer (GLSL define)",
                       {"hierarchical", "dda", "march"});
  return p.getString(
      "tracer", "hierarchical",
      "ray tracer (GLSL define): hierarchical, dda, march through the voxels, or bvh: the scene's "
      "triangles (exact visibility, hits reported in the grid's cells)",
      {"hierarchical", "dda", "march", "bvh"});
}

void addTracerDefine(ShaderDefines& defines, const std::string& tracer) {
  const TracerInfo& info = findTracer(tracer);
  if (!info.glsl)
    fail("tracer '", tracer, "' has no GLSL version (GLSL tracers: hierarchical, dda, march, bvh)");
  defines["VGI_TRACER"] = std::to_string(info.define);
}

std::vector<TraceResult> traceRaysGl(const GlPyramid& pyramid, ShaderLibrary& shaders,
                                     const std::string& tracer, const std::vector<TraceRay>& rays,
                                     Profiler& profiler, uint32_t level, const GpuBvh* bvh) {
  if (tracer == "bvh" && !bvh) fail("tracer 'bvh' needs the scene's BVH on the GPU");
  if (tracer == "bvh" && level > 0) fail("tracer 'bvh' traces triangles: it has no pyramid levels");
  if (level >= pyramid.levels())
    fail("tracer '", tracer, "': level ", level, " is not a level of the pyramid (0 … ", pyramid.levels() - 1,
         ")");
  ShaderDefines defines;
  addTracerDefine(defines, tracer);
  if (level > 0) defines["TRACE_FROM_LEVEL"] = "1";  // (level 0, the benchmarks' case, copies nothing)
  if (bvh) addBvhDefine(defines, *bvh);
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
  pyramid.bind(shaders, prog);
  if (bvh) bvh->bind();
  if (level > 0) shaders.setUniform(prog, "uLevel", level);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_TRACE_RAYS, bufs[0]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_TRACE_HITS, bufs[1]);
  std::vector<glm::uvec4> hits;
  for (size_t b = 0; b < rays.size(); b += batch) {
    const size_t n = std::min(batch, rays.size() - b);
    glNamedBufferSubData(bufs[0], 0, GLsizeiptr(n * sizeof(TraceRay)), rays.data() + b);
    {
      auto s = profiler.scope("trace_" + tracer);
      shaders.setUniform(prog, "uRayCount", uint32_t(n));
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
