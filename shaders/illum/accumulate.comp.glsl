// The sample loop's accumulation (illum/framework/sample_loop.h): sum += sample, per
// pixel, for one channel. Compensated mode is Kahan summation: the rounding
// error of each add is kept in uCompensation and fed into the next, so the
// mean of 10^5 samples stays within a few ulp of the exact mean where one
// float add per sample drifts (tests/illum/modules_test.cpp, SampleLoop.*). `precise`
// keeps the compiler from simplifying (t − sum) − y to zero.
#include "shared/bindings.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = IMAGE_ACCUMULATE_SAMPLE) uniform readonly image2D uSample;
layout(rgba32f, binding = IMAGE_ACCUMULATE_SUM) uniform image2D uSum;
layout(rgba32f, binding = IMAGE_ACCUMULATE_COMPENSATION) uniform image2D uCompensation;
uniform int uCompensated;

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(uSum);
  if (px.x >= size.x || px.y >= size.y) return;
  precise vec4 s = vec4(imageLoad(uSample, px).xyz, 0.0f);
  precise vec4 sum = imageLoad(uSum, px);
  if (uCompensated == 0) {
    imageStore(uSum, px, sum + s);
    return;
  }
  precise vec4 c = imageLoad(uCompensation, px);
  precise vec4 y = s - c;
  precise vec4 t = sum + y;
  precise vec4 nc = (t - sum) - y;
  imageStore(uSum, px, t);
  imageStore(uCompensation, px, nc);
}
