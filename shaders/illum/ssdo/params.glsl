// ssdo's gather pass parameters: one declaration for C++ (illum/methods/ssdo.cpp fills them) and
// GLSL (gather.comp.glsl's block Pass at UBO_PASS). Layout rule: illum/framework/compute_pass.h.
#ifdef __cplusplus
#pragma once
#include "../../shared/cpp_prelude.h"
#endif

SHARED_BEGIN

const int SSDO_PATCH = 0;  // the paper's point samples and sender patches (Ritschel et al. 2009, §3)
const int SSDO_MARCH = 1;  // each direction marched in screen space to its first hit (consistent)

struct SsdoPassParams {
  vec4 viewProj[4];  // this sample's (jittered) view-projection matrix, by columns
  vec4 forward;      // xyz: the camera's view axis (unit); w: unused
  float radius;      // r, world units
  float offset;      // start offset along the normal, in pixels (world size of a pixel at the receiver)
  float thickness;   // world units a surface is taken to extend behind what the camera sees; 0: no limit
  int env;           // directions that meet nothing within r read the environment
  int estimator;     // SSDO_PATCH or SSDO_MARCH
  int steps;         // SSDO_MARCH: points per direction
  int pad0;
  int pad1;
};

SHARED_END
