// voxelpath's path pass parameters: one declaration for C++ (illum/methods/voxelpath.cpp
// fills them) and GLSL (path.comp.glsl's block Pass at UBO_PASS). Layout rule:
// illum/framework/compute_pass.h.
#ifdef __cplusplus
#pragma once
#include "../../shared/cpp_prelude.h"
#endif

SHARED_BEGIN

struct VoxelPathParams {
  vec4 cameraPosition;  // xyz, this sample's
  int maxDepth;         // 1: direct light only
  int rrDepth;          // bounces before Russian roulette
  float clampMax;       // > 0: each vertex's contribution clamped to this (max component)
  int env;              // rays leaving the grid read the environment
  float shadowBias;     // light-map lookups at hits (glossy lobe), texels
  float normalOffset;   // texels
  uint seed;
  uint sampleIndex;
  int writeIndirect;  // the AOVs asked for
  int writeDirect;
  int pad0;
  int pad1;
};

SHARED_END
