// The parameters of the voxel-hit rules (illum/voxel_hits.glsl), one
// declaration for C++ (illum/kits/tracer_kit.h: VoxelHits fills and binds
// it) and GLSL (the std140 block VoxelHits at UBO_VOXEL_HITS). Layout rule:
// illum/framework/compute_pass.h.
#ifdef __cplusplus
#pragma once
#include "../shared/cpp_prelude.h"
#endif

SHARED_BEGIN

// VoxelHitParams::hitPoint: where a hit's path vertex is placed.
const int VOXEL_HIT_ENTRY = 0;   // the voxel entry point (VGI)
const int VOXEL_HIT_CENTRE = 1;  // the voxel's centre
const int VOXEL_HIT_PLANE = 2;   // on the plane of the voxel's mean normal
// VoxelHitParams::backProjection: the RSM back-projection's point.
const int BACK_PROJECTION_ENTRY = 0;  // the voxel entry (VGI)
const int BACK_PROJECTION_PLANE = 1;  // refined on the RSM surface's plane

struct VoxelHitParams {
  float offset;         // ray start offset along the normal, world units
  float voxelDiagonal;  // world units
  float traceLength;    // longer than any ray through the grid
  int glossy;           // 0: the Phong lobes are dropped (diffuse only)
  int backProjection;   // BACK_PROJECTION_*
  int passThrough;      // 1: pass hits in the start's own band (see trace())
  int hitPoint;         // VOXEL_HIT_*
  int pad0;
};

SHARED_END
