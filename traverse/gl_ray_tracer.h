// The OR-mip pyramid on the GPU, for GLSL passes that trace rays through
// shaders/traverse/tracer.glsl (tracer chosen by the VGI_TRACER define), and a
// batch entry point used by the tests (GPU == C++ bit for bit) and the bench.
#pragma once
#include <string>
#include <vector>

#include "core/shader_library.h"
#include "traverse/ray_tracers.h"
#include "voxelize/voxel_grid.h"

namespace vgi {

class ParamSet;
class Profiler;

class GpuGridBuffer;
class GpuBvh;

class GlPyramid {
 public:
  explicit GlPyramid(const OrMipPyramid& pyramid, float marchStep = 0.0f);  // uploads the words
  // A pyramid for grids of `box`, filled on the GPU by build() (per frame for
  // dynamic scenes: no read-back, no CPU pass).
  explicit GlPyramid(const GridBox& box, float marchStep = 0.0f);
  ~GlPyramid();
  GlPyramid(const GlPyramid&) = delete;
  GlPyramid& operator=(const GlPyramid&) = delete;

  // Binds the words at BINDING_PYRAMID and sets the uniforms tracer.glsl
  // declares on `program` (which must be in use).
  void bind(ShaderLibrary& shaders, unsigned program) const;
  const GridBox& box() const { return box_; }
  uint32_t levels() const { return params_.levels; }
  size_t bytes() const { return size_t(totalWords_) * 4; }  // its SSBO

  // Level 0 := the grid's words (a GPU copy, or an upload), then every level
  // above by one dispatch of shaders/traverse/or_mip.comp.glsl — the index
  // kernel of the CPU build, so the words equal OrMipPyramid's.
  void build(const GpuGridBuffer& grid, ShaderLibrary& shaders);
  void build(const BinaryGrid& grid, ShaderLibrary& shaders);
  std::vector<uint32_t> read() const;         // all levels' words
  unsigned words() const { return buffer_; }  // the SSBO (level 0 = the grid's words, first)
  uint64_t countLevel0() const;               // set voxels of the grid (reads level 0 back)

 private:
  void reduce(ShaderLibrary& shaders);
  uint32_t totalWords_ = 0;
  unsigned buffer_ = 0;
  GridBox box_;
  shared::PyramidParams params_{};
  float marchStep_ = 0.0f;
};

// The pyramid's words built on the GPU from a CPU grid (tests compare them
// with OrMipPyramid's).
std::vector<uint32_t> buildOrMipGl(const BinaryGrid& grid, ShaderLibrary& shaders);

// The `tracer` parameter of a GL module: hierarchical (default), dda, march
// or, where triangles make sense, bvh.
std::string readTracerParam(ParamSet& params, bool triangles = true);
// Adds the define that selects a GLSL tracer; throws for tracers GLSL lacks.
void addTracerDefine(ShaderDefines& defines, const std::string& tracer);

// Traces the rays on the GPU with a GLSL tracer ("hierarchical", "dda",
// "march"), from pyramid level `level` up (TracerInputs::level), or "bvh"
// through `bvh` (hits reported in the pyramid's grid). The pass is timed as
// "trace_<tracer>" in `profiler`.
std::vector<TraceResult> traceRaysGl(const GlPyramid& pyramid, ShaderLibrary& shaders,
                                     const std::string& tracer, const std::vector<TraceRay>& rays,
                                     Profiler& profiler, uint32_t level = 0, const GpuBvh* bvh = nullptr);

}  // namespace vgi
