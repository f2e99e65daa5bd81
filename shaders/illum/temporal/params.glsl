// The temporal filter's parameters (illum/framework/temporal.h): one declaration for C++ and GLSL
// (resolve.comp.glsl's block at UBO_PASS). Layout rule: illum/framework/compute_pass.h.
#ifdef __cplusplus
#pragma once
#include "../../shared/cpp_prelude.h"
#endif

SHARED_BEGIN

struct TemporalParams {
  vec4 viewProj[4];          // this frame's view-projection without jitter, by columns
  vec4 previousViewProj[4];  // the previous frame's
  vec4 eye;          // xyz: this frame's camera position; w: a pixel's size per unit distance
  float invSamples;  // 1 / the frame's samples (the film holds their sum)
  float alpha;       // the least weight of the current frame (history length ≤ 1 / alpha)
  float clampSigma;  // history clipped to the 3×3 mean ± clampSigma·σ of the current frame; 0: not
  int hasHistory;    // 0: the first frame of a run (its history is not read)
  float planeTolerance;  // a history texel's surface within this many pixel sizes of the current plane
  float normalCos;       // … and its normal within this cosine of the current one
  int cameraStill;       // 1: the camera did not move since the previous frame
  float currentFrames;   // how many frames the current mean counts as (an animation's frame: 1; the
                         // viewer's standing camera: its samples)
};

SHARED_END
