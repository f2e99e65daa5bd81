// Test probe (tests/illum/compute_pass_test.cpp): a params struct of every
// member kind the layout rule of illum/framework/compute_pass.h allows, for
// C++ and GLSL, and one that breaks it (a vec4 after a lone float).
#ifdef __cplusplus
#pragma once
#include "../../../shaders/shared/cpp_prelude.h"
#endif

SHARED_BEGIN

struct ProbeParams {
  vec4 a;
  vec4 list[3];
  float f0;
  int i0;
  uint u0;
  float f1;
  ivec4 iv;
  uvec4 uv;
  int i1;
  float f2;
  uint u1;
  int pad0;
};

struct MisalignedParams {
  float f0;
  vec4 a;
  float f1;
  float f2;
  float f3;
};

SHARED_END
