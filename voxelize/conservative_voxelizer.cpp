// Comparison voxelizer: conservative rasterization along each triangle's
// dominant axis — Basgier, "Interactive Dynamic Ambient Occlusion Using
// Approximate Voxel Cone Tracing" (M.Sc. thesis, 2015) §3.2–3.3, after Crassin &
// Green 2012 (dominant axis) and Hasselgren et al. 2005 (triangle expansion by
// the pixel semi-diagonal). One draw: the geometry shader picks the axis and
// expands the triangle; each fragment walks the ≤ 3 cells of its column that
// the triangle's plane crosses and keeps those the triangle–box test confirms
// (shaders/shared/triangle_box.glsl, float), so the result approaches the exact
// voxelization without a CPU.
// The hybrid voxelizer (Rauwendaal & Bailey 2013; Basgier 2015 §3.4–3.5) is
// the same pass with small triangles — projected area under the cutoff —
// voxelized triangle-parallel in the geometry shader (conservative.geom.glsl,
// HYBRID): the same triangle–box test decides, so both give the same cells.
#include "voxelize/conservative_voxelizer.h"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/gl_context.h"
#include "core/gl_handles.h"
#include "core/shader_library.h"
#include "shaders/shared/bindings.glsl"
#include "voxelize/gpu_grid.h"

namespace vgi {

namespace {
int viewSide(const VoxelizeRequest& req, const char* name) {
  const glm::uvec3 res = req.box.resolution;
  const int side = int(std::max({res.x, res.y, res.z}));
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &maxSize);
  if (side > maxSize) fail(name, " voxelizer: a ", side, "² view exceeds GL_MAX_FRAMEBUFFER_WIDTH ", maxSize);
  return side;
}
const std::vector<std::string> kFiles = {"voxelize/conservative.vert.glsl", "voxelize/conservative.geom.glsl",
                                         "voxelize/conservative.frag.glsl"};
}  // namespace

BinaryGrid voxelizeConservativeGl(const VoxelizeRequest& req, Profiler& prof, nlohmann::json& stats) {
  VGI_CHECK(req.gl && req.shaders);
  const int side = viewSide(req, "conservative");
  unsigned prog = req.shaders->program(kFiles);
  req.shaders->setUniform(prog, "uViewport", float(side));
  BinaryGrid grid = rasterizeSceneIntoGrid(req, prog, side, side, "conservative", prof);
  stats["passes"] = 1;
  return grid;
}

BinaryGrid voxelizeHybridGl(const VoxelizeRequest& req, Profiler& prof, nlohmann::json& stats) {
  VGI_CHECK(req.gl && req.shaders);
  if (!(req.hybridCutoff >= 0.0f) || !std::isfinite(req.hybridCutoff))
    fail("hybrid voxelizer: cutoff ", req.hybridCutoff, " (cells^2) must be a finite number >= 0");
  const int side = viewSide(req, "hybrid");
  unsigned prog = req.shaders->program(kFiles, {{"HYBRID", "1"}});
  req.shaders->setUniform(prog, "uViewport", float(side));
  req.shaders->setUniform(prog, "uCutoff", req.hybridCutoff);
  GlBuffer counts = makeBuffer(8);
  const uint32_t zero = 0;
  glClearNamedBufferData(counts.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VOXEL_COUNTER, counts.get());
  BinaryGrid grid = rasterizeSceneIntoGrid(req, prog, side, side, "hybrid", prof);
  uint32_t n[2] = {0, 0};
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(counts.get(), 0, 8, n);
  stats["passes"] = 1;
  stats["cutoff_cells2"] = req.hybridCutoff;
  stats["triangles_parallel"] = n[0];  // voxelized in the geometry shader
  stats["fragment_parallel"] = n[1];
  return grid;
}

}  // namespace vgi
