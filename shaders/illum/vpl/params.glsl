// The VPL kit's parameters (illum/kits/vpl_kit.h): one declaration for C++ and GLSL. The gather's
// (gather.comp.glsl's block Pass at UBO_PASS) and the per-VPL shadow-map atlas's (vpl_shadow.glsl's
// block VplShadow at UBO_VPL_SHADOW, read by the gather and by `avg`'s raster of the atlas, which
// fills it). Layout rule: illum/framework/compute_pass.h.
#ifdef __cplusplus
#pragma once
#include "../../shared/cpp_prelude.h"
#endif

SHARED_BEGIN

// VplGatherParams::visibility: how a receiver tests whether it sees a VPL.
const int VPL_VISIBILITY_NONE = 0;         // every VPL is seen
const int VPL_VISIBILITY_VOXELS = 1;       // the two-point test through the voxel grid
const int VPL_VISIBILITY_SHADOW_MAPS = 2;  // the VPL's shadow map in the atlas
// A VPL shadow map's projection (VplShadowParams::kind; illum/vpl/vpl_shadow.glsl).
const int VPL_MAP_PARABOLOID = 0;  // one paraboloid over the VPL's hemisphere
const int VPL_MAP_CUBE = 1;        // six cube faces along the world axes
const int VPL_MAP_HEMICUBE = 2;    // five cube faces in the VPL's frame: its hemisphere

struct VplGatherParams {
  uint chains;         // N
  int bounces;         // VPLs per chain
  float minDistance2;  // the clamp: d² ≥ this in the geometry term
  int visibility;      // VPL_VISIBILITY_*
  float offset;        // the two-point test's offset along each normal, world units
  int pad0;
  int pad1;
  int pad2;
};

struct VplShadowParams {
  int kind;          // VPL_MAP_*
  int res;           // r: a face's side in texels
  int tilesPerRow;   // slots per row of the atlas
  float far;         // the stored distance's unit
  float lift;        // a map's centre: the VPL lifted this far along its normal, world units
  float bias;        // the gather's slack: texels (at the receiver's distance, slope-scaled)
  float tolerance;   // … plus how far the drawn occluders may be from the scene, world units
  int atlasWidth;    // the atlas, texels
  int atlasHeight;
  int pad0;
  int pad1;
  int pad2;
};

SHARED_END
