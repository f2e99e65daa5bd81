// DDGI's shading (Majercik et al. 2019, §5): per image pixel, the diffuse indirect light albedo × the
// probe field's E / π at the G-buffer point (probes.glsl), added to the sample's direct light.
#include "shared/gbuffer.glsl"
#include "shared/octahedral.glsl"
#include "params.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std140, binding = UBO_PASS) uniform Pass { DdgiParams pass; };
#include "probes.glsl"
layout(rgba32f, binding = IMAGE_SAMPLE) uniform image2D uSample;  // holds the direct light
layout(rgba32f, binding = IMAGE_SAMPLE_AOV0) uniform writeonly image2D uIndirectAov;
layout(rgba32f, binding = IMAGE_SAMPLE_AOV1) uniform writeonly image2D uDirectAov;

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(px, imageSize(uSample)))) return;
  vec4 direct = imageLoad(uSample, px);
  vec4 P = texelFetch(gPosition, px, 0);
  vec3 indirect = vec3(0.0f);
  if (P.w != 0.0f) {
    vec3 n = normalize(texelFetch(gNormal, px, 0).xyz);
    vec3 v = normalize(pass.camera.xyz - P.xyz);
    indirect = texelFetch(gAlbedo, px, 0).xyz * probeIrradiance(P.xyz, n, v);
  }
  imageStore(uSample, px, vec4(direct.xyz + indirect, 1.0f));
  if (pass.writeDirect != 0) imageStore(uDirectAov, px, vec4(direct.xyz, 1.0f));
  if (pass.writeIndirect != 0) imageStore(uIndirectAov, px, vec4(indirect, 1.0f));
}
