#include "voxelize/gpu_grid.h"

#include <glad/gl.h>

#include "core/error.h"
#include "core/gpu_scene.h"
#include "core/profiler.h"
#include "core/shader_library.h"
#include "shaders/shared/bindings.glsl"
#include "voxelize/voxelizer.h"

namespace vgi {

void setGridUniforms(ShaderLibrary& shaders, unsigned program, const GridBox& box) {
  const shared::GridParams g = box.params();
  shaders.setUniform(program, "uOrigin", g.origin);
  shaders.setUniform(program, "uAxisX", g.axisX);
  shaders.setUniform(program, "uAxisY", g.axisY);
  shaders.setUniform(program, "uAxisZ", g.axisZ);
  shaders.setUniform(program, "uResolution", g.resolution);
}

void drawWithoutAttachments(int width, int height, const std::function<void()>& draw) {
  unsigned fbo = 0;
  glCreateFramebuffers(1, &fbo);
  glNamedFramebufferParameteri(fbo, GL_FRAMEBUFFER_DEFAULT_WIDTH, width);
  glNamedFramebufferParameteri(fbo, GL_FRAMEBUFFER_DEFAULT_HEIGHT, height);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  draw();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteFramebuffers(1, &fbo);
}

BinaryGrid rasterizeSceneIntoGrid(const VoxelizeRequest& req, unsigned program, int width, int height,
                                  const std::string& passName, Profiler& prof) {
  BinaryGrid grid(req.box);
  std::unique_ptr<GpuScene> gpu;
  {
    auto s = prof.scope("upload");
    gpu = std::make_unique<GpuScene>(*req.scene, req.time);
  }
  setGridUniforms(*req.shaders, program, req.box);
  GpuGridBuffer target(req.box);
  {
    auto s = prof.scope(passName);
    drawWithoutAttachments(width, height, [&] {
      glUseProgram(program);
      target.bind(BINDING_GRID_WORDS);
      gpu->draw();
    });
  }
  {
    auto s = prof.scope("readback");
    target.read(grid);
  }
  return grid;
}

GpuGridBuffer::GpuGridBuffer(const GridBox& box)
    : bytes_(size_t(box.resolution.x) * box.resolution.y * (box.resolution.z / 32u) * sizeof(uint32_t)) {
  glCreateBuffers(1, &buffer_);
  glNamedBufferStorage(buffer_, GLsizeiptr(bytes_), nullptr, GL_DYNAMIC_STORAGE_BIT);
  const uint32_t zero = 0;
  glClearNamedBufferData(buffer_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

GpuGridBuffer::~GpuGridBuffer() { glDeleteBuffers(1, &buffer_); }

void GpuGridBuffer::bind(unsigned binding) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer_);
}

void GpuGridBuffer::read(BinaryGrid& grid) const {
  VGI_CHECK(grid.words().size() * sizeof(uint32_t) == bytes_);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(buffer_, 0, GLsizeiptr(bytes_), grid.words().data());
}

}  // namespace vgi
