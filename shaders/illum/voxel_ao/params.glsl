// voxel_ao's gather pass parameters: one declaration for C++ (illum/methods/voxel_ao.cpp
// fills them) and GLSL (ao.comp.glsl's block Pass at UBO_PASS). Layout rule:
// illum/framework/compute_pass.h.
#ifdef __cplusplus
#pragma once
#include "../../shared/cpp_prelude.h"
#endif

SHARED_BEGIN

struct VoxelAoParams {
  float radius;         // r, world units
  float offset;         // start offset along the normal, world units
  float voxelDiagonal;  // world units
  int passThrough;      // 1: hits that may be the receiver's own voxel are passed
};

SHARED_END
