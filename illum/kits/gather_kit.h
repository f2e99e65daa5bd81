// The screen-space gather kit that hemisphere-gathering GL modules share
// (nearfield, voxel_ao, vct, vct_ao, vpl; shaders/illum/gather/): a gather buffer at 1, ½ or ¼
// of the image resolution, the interleaved direction sets its gather pass
// reads (GATHER_DIRECTIONS in gather.glsl), the geometry-aware blur over the
// interleave window and the joint bilateral upsampling with its composite
// into the frame's sample image. Each method's gather shader runs the one entry of
// gather_pass.glsl (the pixel, its receiver, the empty pixel) and defines only its per-pixel work.
#pragma once
#include <string>

#include "illum/framework/compute_pass.h"
#include "shaders/illum/gather/params.glsl"

namespace vgi {

class Frame;
class ParamSet;

struct GatherSettings {
  int rays = 16;
  float resolution = 0.5f;  // 1, 0.5 or 0.25 of the image
  int interleave = 4;       // k: k×k blocks of k² direction sets
  bool blur = true;
  // true: the gathered E is reflected light (sample += albedo × E over the
  // direct light already in the sample); false: the sample is E itself (AO).
  bool reflect = true;
};
// Reads rays (unless !rays: a gather without directions), resolution,
// interleave and blur (`what` names the gathered quantity in the docs).
GatherSettings readGatherParams(ParamSet& params, const std::string& what, bool reflect, bool rays = true,
                                int interleaveDefault = 4);

class GatherKit {
 public:
  // Once per frame: the gather buffers (the frame's scratch textures) and programs.
  void prepare(Frame& frame, const GatherSettings& settings);
  // Throws unless a gather pass's block Gather (shaders/illum/gather/params.glsl) has the C++
  // layout; once per pass, after it is created.
  static void checkPass(const ComputePassBase& pass);
  // This sample's directions (GATHER_DIRECTIONS): sample 0 unrotated, later ones rotated.
  void setSample(int sample);
  // Binds the gather buffer at IMAGE_OUTPUT and dispatches the program in use
  // over it, in batches of `perDispatch` of its `items` (rays, cones, VPL chains):
  // the kit's parameters (its block at UBO_GATHER) with each batch's range
  // (gather.glsl says why).
  void dispatchGather(int items, int perDispatch);
  // The kit's ray-gathering modules' batch: 16 rays of up to 4 traces each
  // stay under llvmpipe's 65535 loop iterations per invocation.
  static constexpr int kRaysPerDispatch = 16;
  // Blur (when on and k > 1), then upsampling + composite into the sample
  // image, and the "indirect" / "direct" outputs when asked for; timed as
  // "blur" and "upsample_composite" (or "composite" at full resolution).
  void resolve(Frame& frame);
  // A second quantity of the gather (an RGBA32F image of the gather size, w = 1
  // on a surface; e.g. vct's AO) through the same blur and upsampling into the
  // full-resolution RGBA32F texture `full` (the value itself, no composite);
  // timed as "blur_<name>" and "upsample_<name>".
  void resolveValue(Frame& frame, unsigned low, unsigned full, const std::string& name);

  int width() const { return lw_; }
  int scale() const { return scale_; }  // image pixels per gather pixel
  unsigned gatherTexture() const {
    return low_[0];
  }  // what the gather pass writes (RGBA32F, w = 1 on a surface)
  int height() const { return lh_; }
  int blurWindow() const { return blur_ ? s_.interleave : 0; }
  const GatherSettings& settings() const { return s_; }

 private:
  GatherSettings s_;
  int scale_ = 1, lw_ = 0, lh_ = 0;
  bool blur_ = false;
  UniformBlock<shared::GatherParams> block_;
  // Uploads the parameters and binds them at UBO_GATHER.
  void upload();
  // The blur (when on) of `low` into the second buffer; returns what the upsampling reads.
  unsigned blurInto(Frame& f, unsigned low, const char* pass);
  // The upsampling of `input` into the images bound at IMAGE_SAMPLE (…_AOV0/1).
  void upsample(Frame& f, unsigned input);
  unsigned low_[2] = {0, 0};  // gathered, blurred
  unsigned blurProg_ = 0, upProg_ = 0;
};

}  // namespace vgi
