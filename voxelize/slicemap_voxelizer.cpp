// Comparison voxelizer: single-pass slicemap voxelization — Eisemann &
// Décoret, "Fast Scene Voxelization and Applications", I3D 2006. All triangles
// are rasterized once in an orthographic view along the grid's depth axis at
// W×H; each fragment's depth selects the bit it ORs into its column. One
// fragment per pixel centre and triangle: triangles seen at grazing angles
// (parallel to the depth axis) leave holes, which the VGI paper's §3.3 and
// Fig. 4 compare against.
#include "voxelize/slicemap_voxelizer.h"

#include <glad/gl.h>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/gl_context.h"
#include "core/shader_library.h"
#include "voxelize/gpu_grid.h"

namespace vgi {

BinaryGrid voxelizeSlicemapGl(const VoxelizeRequest& req, Profiler& prof, nlohmann::json& stats) {
  VGI_CHECK(req.gl && req.shaders);
  const glm::uvec3 res = req.box.resolution;
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &maxSize);
  if (int(res.x) > maxSize || int(res.y) > maxSize)
    fail("slicemap voxelizer: a ", res.x, "x", res.y, " view exceeds GL_MAX_FRAMEBUFFER_WIDTH ", maxSize);
  unsigned prog = req.shaders->program({"voxelize/slicemap.vert.glsl", "voxelize/slicemap.frag.glsl"});
  BinaryGrid grid = rasterizeSceneIntoGrid(req, prog, int(res.x), int(res.y), "slicemap", prof);
  stats["passes"] = 1;
  return grid;
}

}  // namespace vgi
