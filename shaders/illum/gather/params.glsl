// The gather kit's parameters (illum/kits/gather_kit.h): one declaration for C++ (the kit fills and
// uploads them before each of its dispatches) and GLSL (gather.glsl's block Gather at UBO_GATHER), read
// by the method's gather pass, the blur and the upsampling. Layout rule: illum/framework/compute_pass.h.
#ifdef __cplusplus
#pragma once
#include "../../shared/cpp_prelude.h"
#endif

SHARED_BEGIN

struct GatherParams {
  vec4 camera;    // xyz: the camera position (the geometry weights); w: the world size of one
                  // full-resolution pixel per unit distance
  vec4 rotation;  // xy: this sample's Cranley–Patterson rotation of the directions (GATHER_DIRECTIONS)
  int scale;      // image pixels per gather pixel: 1, 2 or 4
  int rays;       // N: directions per gather pixel (GATHER_DIRECTIONS)
  int interleave;  // k: k×k blocks of k² direction sets (VPL subsets)
  int frame;       // the sample index: each interleave block adds its own rotation
  int batchFirst;  // this dispatch's items (rays, cones, VPL chains): batchFirst … batchEnd − 1
  int batchEnd;
  int accumulate;     // 1: add to what the sample's earlier dispatches stored (gatheredBefore)
  int composite;      // the upsampling: 0 albedo × E over the sample's direct light; 1 E itself
  int writeIndirect;  // the upsampling: 1 writes the indirect part to its output channel
  int writeDirect;    // … and the direct part to its own
  float visibilityOffset;  // GATHER_VISIBILITY: both ends of a neighbour's test lifted this far, world units
  int pad1;
};

SHARED_END
