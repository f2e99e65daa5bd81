// The screen-space gather kit that hemisphere-gathering GL modules share
// (nearfield, ssdo, voxel_ao, vct, vct_ao, vpl; shaders/illum/gather/): a gather buffer at 1, ½ or ¼
// of the image resolution, the interleaved direction sets its gather pass
// reads (GATHER_DIRECTIONS in gather.glsl), the geometry-aware blur over the
// interleave window and the joint bilateral upsampling with its composite
// into the frame's sample image. Each method's gather shader runs the one entry of
// gather_pass.glsl (the pixel, its receiver, the empty pixel) and defines only its per-pixel work.
// Two remedies for light carried across thin walls, parameters of the methods that can trace
// (nearfield; docs/BENCHMARKS.md, "Remedies"): `blur_visibility` — the blur and the upsampling
// weigh only neighbours that the method's voxels connect to the pixel (an edge mask of two short
// traces per gather pixel, shaders/illum/gather/visibility.glsl); `fixup` — an image pixel none of
// whose gather pixels lies on its surface (a wall's face, a pole) is gathered again at full rate by
// the method's own pass compiled with GATHER_FIXUP (gather.glsl), instead of borrowing a neighbour's.
#pragma once
#include <functional>
#include <string>

#include "core/gl_handles.h"
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
  // The blur and the upsampling weigh only neighbours the method's voxels show the receiver
  // (GATHER_VISIBILITY in gather.glsl): no light carried across a thin wall between coplanar surfaces.
  bool visibility = false;
  // Image pixels with no gather pixel on their surface are gathered again at full rate
  // (GATHER_FIXUP in gather.glsl) instead of borrowing the closest neighbour's light.
  bool fixup = false;
};
// Reads rays (unless !rays: a gather without directions), resolution,
// interleave and blur (`what` names the gathered quantity in the docs).
GatherSettings readGatherParams(ParamSet& params, const std::string& what, bool reflect, bool rays = true,
                                int interleaveDefault = 4);
// Reads blur_visibility (a method whose voxel tracer the kit's passes may use) and fixup (a method
// whose gather pass compiles with GATHER_FIXUP).
void readGatherWallParams(ParamSet& params, GatherSettings& s, bool visibilityByDefault, bool fixupByDefault);

// A render's seed as a shift of its samples' pattern rotations (a Cranley–Patterson rotation of
// the whole sequence): 0 for seed 1, the default, so its images stay what they were; for another seed
// the (seed − 1)-th point of the R2 sequence (Roberts 2018), so that `--seed` (and `vgi compare
// --seeds`) draw other directions from methods whose samples otherwise follow the sample index.
glm::vec2 seedShift(uint32_t seed);

class GatherKit {
 public:
  // Once per frame: the gather buffers (the frame's scratch textures) and programs. With
  // settings.visibility, the blur and upsampling trace the tracer of `tracerDefines` (bound by
  // resolve's bindTracer), both ends lifted visibilityOffset (world units) along their normals.
  void prepare(Frame& frame, const GatherSettings& settings, const ShaderDefines& tracerDefines = {},
               float visibilityOffset = 0.0f);
  // Throws unless a gather pass's block Gather (shaders/illum/gather/params.glsl) has the C++
  // layout; once per pass, after it is created.
  static void checkPass(const ComputePassBase& pass);
  // This sample's directions (GATHER_DIRECTIONS): sample 0 unrotated, later ones rotated; the
  // whole sequence shifted by the render's seed (seedShift).
  void setSample(int sample, uint32_t seed);
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
  // bindTracer binds the tracer to the kit's program in use (settings.visibility); with
  // settings.fixup, fixupGather makes the method's gather pass compiled with GATHER_FIXUP current
  // (its parameters those of this sample's gather, its inputs bound) and calls dispatchFixup.
  void resolve(Frame& frame, const std::function<void(unsigned program)>& bindTracer = {},
               const std::function<void()>& fixupGather = {});
  // The fix-up run of the program in use over the listed pixels, in batches as dispatchGather.
  void dispatchFixup(int items, int perDispatch);
  // A second quantity of the gather (an RGBA32F image of the gather size, w = 1
  // on a surface; e.g. vct's AO) through the same blur and upsampling into the
  // full-resolution RGBA32F texture `full` (the value itself, no composite);
  // timed as "blur_<name>" and "upsample_<name>".
  void resolveValue(Frame& frame, unsigned low, unsigned full, const std::string& name,
                    const std::function<void(unsigned program)>& bindTracer = {});

  // With settings.fixup: "fixup_pixels", the pixels the last sample gathered again at full rate, and
  // the fix-up list's bytes as method state (Frame::addStateBytes).
  void stats(Frame& frame) const;
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
  // The program in use over width × height (or, `indirect` ≠ 0, the groups that buffer holds at
  // byte 4) in batches of perDispatch of `items` (batch range, accumulate), with the image barrier
  // after each and the fetch barrier at the end.
  void dispatchBatches(int items, int perDispatch, int width, int height, unsigned indirect = 0);
  // The blur (when on) of `low` into the second buffer; returns what the upsampling reads.
  unsigned blurInto(Frame& f, unsigned low, const char* pass,
                    const std::function<void(unsigned)>& bindTracer);
  // The upsampling of `input` into the images bound at IMAGE_SAMPLE (…_AOV0/1).
  void upsample(Frame& f, unsigned input, const std::function<void(unsigned)>& bindTracer);
  unsigned low_[2] = {0, 0};  // gathered, blurred
  unsigned blurProg_ = 0, upProg_ = 0, edgesProg_ = 0;
  unsigned edges_ = 0;                        // settings.visibility: the edge mask (R32UI, gather size)
  unsigned listProg_ = 0, fixupTexture_ = 0;  // settings.fixup: the classifying upsampling, the fix-ups
  GlBuffer fixupList_;                        // its list (gather.glsl: GatherFixup)
  size_t fixupListBytes_ = 0;
  int fullW_ = 0, fullH_ = 0;
  // settings.visibility: the edge mask of this sample's G-buffer, bound at TEXUNIT_PASS_INPUT2.
  void edges(Frame& f, const std::function<void(unsigned)>& bindTracer);
  // settings.fixup: the list of pixels without a gather pixel on their surface and their
  // full-rate gather (fixupGather), bound at TEXUNIT_GATHER_FIXUP; timed as "fixup".
  void fixup(Frame& f, unsigned input, const std::function<void(unsigned)>& bindTracer,
             const std::function<void()>& fixupGather);
};

}  // namespace vgi
