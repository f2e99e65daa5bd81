// nearfield's indirect pass parameters: one declaration for C++
// (illum/methods/nearfield.cpp fills them) and GLSL (indirect.comp.glsl's
// block Pass at UBO_PASS). Layout rule: illum/framework/compute_pass.h.
#ifdef __cplusplus
#pragma once
#include "../../shared/cpp_prelude.h"
#endif
#include "../voxel_hit_params.glsl"

SHARED_BEGIN

struct NearFieldPassParams {
  float radius;         // r, world units
  float offset;         // start offset along the normal, world units
  float voxelDiagonal;  // world units
  int env;              // rays that leave r read the environment
  int passThrough;      // 1: rays go on past empty-looking and own voxels (see main)
  int backProjection;   // BACK_PROJECTION_* (voxel_hit_params.glsl)
  int pad0;
  int pad1;
};

SHARED_END
