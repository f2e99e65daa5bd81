// What the many-light GL modules share (vpl: VGI §5.3; avg: approximate
// visibility grids): the VPL buffer (shaders/shared/vpl.glsl: N chains of up
// to `bounces` VPLs, bounce-major), and the deferred + interleaved gather
// from it (shaders/illum/vpl/gather.comp) in the gather kit's buffer — with
// voxel, shadow-map or no visibility on the GPU, or exact (Embree) visibility
// on the CPU from the same VPLs — then the kit's blur, upsampling and
// composite; the VPL stats.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "core/gl_handles.h"
#include "illum/framework/method.h"
#include "illum/kits/gather_kit.h"
#include "shaders/illum/vpl/params.glsl"
#include "shaders/shared/vpl.glsl"

namespace vgi {

class Frame;
class ParamSet;
class ShaderLibrary;

enum class VplVisibility { None, Voxels, ShadowMaps, Exact };

struct VplSettings {
  int chains = 1024;
  int bounces = 2;
  GatherSettings gather;
  float clamp =
      0.005f;  // of the scene diagonal (docs/BENCHMARKS.md: 0.02 lost 8 % of the indirect light on Sibenik)
  VplVisibility visibility = VplVisibility::Voxels;
  float offset = 1.0f;  // voxel visibility: both ends moved along their normals, voxel diagonals
  float exactLift =
      0;  // exact visibility: the VPL end moved this far along its normal (world; 0: 1e-4 · diagonal)
};
// Reads vpls (default `chains`), the gather layout (interleave, resolution,
// blur) and clamp; the module reads bounces, visibility and offset.
void readVplParams(ParamSet& params, VplSettings& s);
// Throws, naming vpls and bounces, if their VPL buffer would exceed 256 MiB (4M VPLs).
void checkVplMemory(const VplSettings& s);
// The exact counterpart of a VPL method whose chains carry `bounces` VPLs: full path tracing to
// bounces + 1 vertices after the camera's (vpl, avg).
Counterpart vplChainsCounterpart(const nlohmann::json& params);
// The rotation of the chains' R2 points (shared/sampling.glsl: r2Point) for
// sample k of a run seeded `seed`: a hash of (k, seed), sample 0 included. (Sample 0 was once left
// unrotated: every seed then drew the same first VPLs, so a render of a few samples was one fixed
// quadrature — on an atrium lit through its opening 64 VPLs gave 1.3–1.5× the indirect energy of 1024,
// in the same hot pixels for every seed; issue 64 §3.)
glm::uvec2 vplRotation(int k, uint32_t seed);

class VplKit {
 public:
  // Once per frame: the gather buffers and program, the VPL buffer (kept).
  // `tracer` is the voxel tracer's define (voxel visibility), voxelDiagonal
  // the grid's (0 without one), sceneDiagonal the clamp's unit.
  void prepare(Frame& f, const VplSettings& s, const std::string& tracer, float voxelDiagonal,
               float sceneDiagonal);
  unsigned vplBuffer() const { return vpls_.get(); }
  // The shadow-map atlas's layout the gather reads (zero, unused, without shadow maps): `avg` fills
  // it before the first gather and binds it for its raster with bindShadowParams.
  shared::VplShadowParams& shadowParams() { return shadow_.value; }
  void bindShadowParams();
  // The gather of this sample ("gather" is timed by the caller); bindExtra
  // binds what the visibility reads besides the G-buffer and the VPLs
  // (the pyramid, the shadow atlas) to the gather program.
  void gather(Frame& f, const std::function<void(unsigned program)>& bindExtra);
  // The kit's blur and upsampling; with the gather kit's remedies (vpl, visibility=voxels) bindExtra
  // binds the tracer to their programs and to the gather's fix-up run.
  void resolve(Frame& f, const std::function<void(unsigned program)>& bindExtra = {});
  std::vector<shared::Vpl> read() const;
  void write(const std::vector<shared::Vpl>& v) const;
  // vpls_placed and vpl_flux per bounce (the last sample's), the clamp, the gather size; the VPL
  // buffer's bytes as method state (Frame::addStateBytes).
  void stats(Frame& f) const;
  float minDistance2() const { return dMin_ * dMin_; }

 private:
  void gatherExact(Frame& f);
  VplSettings s_;
  GatherKit kit_;
  GlBuffer vpls_;
  size_t slots_ = 0;
  ComputePass<shared::VplGatherParams> gather_;
  ComputePass<shared::VplGatherParams> gatherFixup_;  // settings.gather.fixup: at listed pixels
  // Batches of chains per gather dispatch (llvmpipe's loop limit: gather.glsl).
  int chainBatches() const;
  int chainsPerDispatch() const;
  UniformBlock<shared::VplShadowParams> shadow_;
  float dMin_ = 0, sceneDiagonal_ = 0;
};

}  // namespace vgi
