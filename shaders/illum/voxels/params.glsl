// `voxels`' view pass parameters: one declaration for C++ (illum/methods/voxels.cpp fills them)
// and GLSL (view.comp.glsl's block Pass at UBO_PASS). Layout rule: illum/framework/compute_pass.h.
#ifdef __cplusplus
#pragma once
#include "../../shared/cpp_prelude.h"
#endif

SHARED_BEGIN

struct VoxelViewParams {
  vec4 invViewProj[4];  // the jittered camera's inverse view-projection, column by column
  vec4 eye;             // xyz: the eye; w: the camera's cut-away distance (> 0: rays start on the near plane)
  vec4 forward;         // xyz: the view axis (unit)
  float nearest;        // the depth cue's range: the distances from the eye to the scene's bounds
  float farthest;
  uint level;  // the pyramid level shown (0: the grid)
  uint pad0;
};

SHARED_END
