// reference_gl's pass parameters: one declaration for C++ (illum/methods/reference_gl.cpp fills them)
// and GLSL (exact.glsl's block Pass at UBO_PASS, read by ao.comp.glsl and path.comp.glsl). Layout
// rule: illum/framework/compute_pass.h.
#ifdef __cplusplus
#pragma once
#include "../../shared/cpp_prelude.h"
#endif

SHARED_BEGIN

// glossy (illum/kits/exact_params.h, GlossyModel): the surfaces that reflect by their Phong lobe.
#define GLOSSY_ALL 0
#define GLOSSY_FIRST 1
#define GLOSSY_DIRECT 2

struct ReferenceGlParams {
  vec4 eye;      // xyz: the reference's pinhole; w: the camera's cut-away distance (> 0: rays start on
                 // the near plane, PinholeView::origin)
  vec4 forward;  // xyz: the view axis
  vec4 right;    // xyz: scaled by tan(fov/2)·aspect (illum/framework/deferred.h, PinholeView)
  vec4 up;       // xyz: scaled by tan(fov/2)
  float eps;     // the start offset's scene part (2e-5 of the diagonal, as the reference's)
  float radius;  // ao, nearfield: world units
  uint sampleIndex;
  uint seed;
  int maxDepth;         // path
  int rrDepth;          // path: Russian roulette from this depth
  int env;              // 1: the environment lights the scene (path, direct, nearfield)
  int envIndirect;      // path: 1: the environment seen from x0 counts as indirect
  int deltaLights;      // the scene's own delta lights: the GPU scene's first lights
  int emitterCount;     // emissive triangles
  int emitterSampling;  // EMITTER_SAMPLING_*
  int writeIndirect;    // 1: the indirect part to its output channel
  int writeDirect;      // … and the direct part to its own
  int glossy;           // path, nearfield: GLOSSY_*
  int pad1;
  int pad2;
};

SHARED_END
