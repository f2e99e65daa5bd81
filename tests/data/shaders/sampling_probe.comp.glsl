// Test probe (tests/core/sampling_test.cpp): the shared random numbers and R2
// points as bits, per invocation i: the first four numbers of stream
// rngSeed(i, uB, uC), then r2Point(i · 977, uRx, uRy).
#include "../../../shaders/shared/bindings.glsl"
#include "../../../shaders/shared/sampling.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = BINDING_TRACE_HITS) writeonly buffer Results { uint results[]; };  // 6 per invocation
uniform uint uB;
uniform uint uC;
uniform uint uRx;
uniform uint uRy;
uniform int uCount;
void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= uCount) return;
  uint state = rngSeed(uint(i), uB, uC);
  for (int k = 0; k < 4; ++k) results[6 * i + k] = floatBitsToUint(rngNext(state));
  vec2 r = r2Point(uint(i) * 977u, uRx, uRy);
  results[6 * i + 4] = floatBitsToUint(r.x);
  results[6 * i + 5] = floatBitsToUint(r.y);
}
