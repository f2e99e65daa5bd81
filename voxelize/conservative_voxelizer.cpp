// Comparison voxelizer: conservative rasterization along each triangle's
// dominant axis — Basgier, "Interactive Dynamic Ambient Occlusion Using
// Approximate Voxel Cone Tracing" (M.Sc. thesis, 2015) §3.2–3.3, after Crassin &
// Green 2012 (dominant axis) and Hasselgren et al. 2005 (triangle expansion by
// the pixel semi-diagonal). One draw: the geometry shader picks the axis and
// expands the triangle; each fragment walks the ≤ 3 cells of its column that
// the triangle's plane crosses and keeps those the triangle–box test confirms
// (shaders/shared/triangle_box.glsl, float), so the result approaches the exact
// voxelization without a CPU.
#include "voxelize/conservative_voxelizer.h"

#include <glad/gl.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/gl_context.h"
#include "core/shader_library.h"
#include "voxelize/gpu_grid.h"

namespace vgi {

BinaryGrid voxelizeConservativeGl(const VoxelizeRequest& req, Profiler& prof, nlohmann::json& stats) {
  VGI_CHECK(req.gl && req.shaders);
  const glm::uvec3 res = req.box.resolution;
  const int side = int(std::max({res.x, res.y, res.z}));
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &maxSize);
  if (side > maxSize)
    fail("conservative voxelizer: a ", side, "² view exceeds GL_MAX_FRAMEBUFFER_WIDTH ", maxSize);
  unsigned prog = req.shaders->program({"voxelize/conservative.vert.glsl", "voxelize/conservative.geom.glsl",
                                        "voxelize/conservative.frag.glsl"});
  req.shaders->setUniform(prog, "uViewport", float(side));
  BinaryGrid grid = rasterizeSceneIntoGrid(req, prog, side, side, "conservative", prof);
  stats["passes"] = 1;
  return grid;
}

}  // namespace vgi
