// Test probe (tests/illum/compute_pass_test.cpp): copies every member of the
// ProbeParams block (or, with MISALIGNED, declares the MisalignedParams one)
// into a buffer as bits, in declaration order.
#include "../../../shaders/shared/bindings.glsl"
#include "pass_params_probe.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = BINDING_TRACE_HITS) writeonly buffer Results { uint results[]; };
#ifdef MISALIGNED
layout(std140, binding = UBO_PASS) uniform Pass { MisalignedParams pass; };
void main() { results[0] = floatBitsToUint(pass.f0 + pass.a.x + pass.f1 + pass.f2 + pass.f3); }
#else
layout(std140, binding = UBO_PASS) uniform Pass { ProbeParams pass; };
void put(inout int k, vec4 v) {
  for (int c = 0; c < 4; ++c) results[k++] = floatBitsToUint(v[c]);
}
void main() {
  int k = 0;
  put(k, pass.a);
  for (int j = 0; j < 3; ++j) put(k, pass.list[j]);
  results[k++] = floatBitsToUint(pass.f0);
  results[k++] = uint(pass.i0);
  results[k++] = pass.u0;
  results[k++] = floatBitsToUint(pass.f1);
  for (int c = 0; c < 4; ++c) results[k++] = uint(pass.iv[c]);
  for (int c = 0; c < 4; ++c) results[k++] = pass.uv[c];
  results[k++] = uint(pass.i1);
  results[k++] = floatBitsToUint(pass.f2);
  results[k++] = pass.u1;
  results[k++] = uint(pass.pad0);
}
#endif
