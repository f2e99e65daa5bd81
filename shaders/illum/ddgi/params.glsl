// ddgi's parameters: one declaration for C++ (illum/methods/ddgi.cpp fills them) and GLSL (the
// probe field's block at UBO_PASS in its passes, probes.glsl). Layout rule: illum/framework/compute_pass.h.
#ifdef __cplusplus
#pragma once
#include "../../shared/cpp_prelude.h"
#endif

SHARED_BEGIN

const int DDGI_IRRADIANCE_TILE = 8;  // texels per probe tile side: 6 × 6 interior + the border
const int DDGI_DISTANCE_TILE = 16;   // 14 × 14 + the border

struct DdgiParams {
  vec4 origin;     // xyz: probe (0, 0, 0)'s position; w: the bias (world units) of a query point
  vec4 spacing;    // xyz: between neighbouring probes; w: the longest distance a probe stores
  ivec4 counts;    // xyz: probes per axis; w: probes per row of the textures' atlas
  vec4 rotation[3];  // this update's random rotation of the ray directions (rows)
  vec4 camera;       // xyz: the camera position (the shading pass's view bias); w: unused
  int rays;          // per probe per update
  int env;           // rays that meet nothing read the environment
  float hysteresis;  // this update's weight of the old texel (0 on the first update)
  int writeDirect;   // the shading pass: 1 writes the direct part to its output channel
  int writeIndirect;  // … and the indirect part
  int relocate;       // 1: back faces are told apart, probes move out of geometry and stuck ones are left out
  int move;           // the relocation pass: 1 moves the probes (warm-up), 0 only classifies them
  int pad0;
};

SHARED_END
