// Comparison voxelizer: single-pass slicemap voxelization — Eisemann &
// Décoret, "Fast Scene Voxelization and Applications", I3D 2006. All triangles
// are rasterized once in an orthographic view along the grid's depth axis at
// W×H; each fragment's depth selects the bit it ORs into its column. One
// fragment per pixel centre and triangle: triangles seen at grazing angles
// (parallel to the depth axis) leave holes, which the VGI paper's §3.3 and
// Fig. 4 compare against.
#include "voxelize/slicemap_voxelizer.h"

#include <glad/gl.h>

#include "core/error.h"
#include "core/gl_context.h"
#include "core/gpu_scene.h"
#include "core/shader_library.h"
#include "voxelize/gpu_grid.h"

namespace vgi {

BinaryGrid voxelizeSlicemapGl(const VoxelizeRequest& req, Profiler& prof, nlohmann::json& stats) {
  VGI_CHECK(req.gl && req.shaders);
  BinaryGrid grid(req.box);
  const glm::uvec3 res = req.box.resolution;
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &maxSize);
  if (int(res.x) > maxSize || int(res.y) > maxSize)
    fail("slicemap voxelizer: a ", res.x, "x", res.y, " view exceeds GL_MAX_FRAMEBUFFER_WIDTH ", maxSize);
  unsigned prog = req.shaders->program({"voxelize/slicemap.vert.glsl", "voxelize/slicemap.frag.glsl"});
  std::unique_ptr<GpuScene> gpu;
  {
    auto s = prof.scope("upload");
    gpu = std::make_unique<GpuScene>(*req.scene, req.time);
  }
  setGridUniforms(prog, req.box);
  GpuGridBuffer target(req.box);
  unsigned fbo = 0;
  glCreateFramebuffers(1, &fbo);  // no attachments: fragments only write the SSBO
  glNamedFramebufferParameteri(fbo, GL_FRAMEBUFFER_DEFAULT_WIDTH, GLint(res.x));
  glNamedFramebufferParameteri(fbo, GL_FRAMEBUFFER_DEFAULT_HEIGHT, GLint(res.y));
  {
    auto s = prof.scope("slicemap");
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, GLsizei(res.x), GLsizei(res.y));
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glUseProgram(prog);
    target.bind(0);
    gpu->draw();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }
  {
    auto s = prof.scope("readback");
    target.read(grid);
  }
  glDeleteFramebuffers(1, &fbo);
  stats["passes"] = 1;
  return grid;
}

}  // namespace vgi
