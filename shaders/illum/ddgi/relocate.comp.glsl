// DDGI's probe relocation and classification (illum/methods/ddgi.cpp; the rule is ours, after the
// relocation and the probe states of the RTXGI SDK that Majercik, Marrs, Spjut, McGuire, "Scaling
// Probe-Based Real-Time Dynamic Global Illumination for Production", JCGT 10(2), 2021, describe): one
// invocation per probe, from the last update's rays. A probe whose rays met back faces more than a
// quarter of the time is inside geometry; with pass.move it steps through the nearest back face, past
// it by half the least surface distance; a probe outside but closer than that distance (0.2 of the
// least spacing) to a surface steps away from it. An offset stays within 0.45 spacings of the grid
// point, so the probe stays in its cell. The state (w) is 1 for a probe outside, 0 for one inside:
// the query leaves those out.
#include "shared/bindings.glsl"
#include "shared/constants.glsl"
#include "params.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std140, binding = UBO_PASS) uniform Pass { DdgiParams pass; };
#include "rays.glsl"
layout(rgba32f, binding = IMAGE_OUTPUT2) uniform readonly image2D uRays;
layout(std430, binding = BINDING_DDGI_PROBES) buffer DdgiProbes { vec4 probeStates[]; };

void main() {
  int p = int(gl_GlobalInvocationID.x);
  if (gl_GlobalInvocationID.y != 0u || p >= pass.counts.x * pass.counts.y * pass.counts.z) return;
  int back = 0;
  float nearestBack = 1e30f, nearestFront = 1e30f;
  vec3 backDir = vec3(0.0f), frontDir = vec3(0.0f);
  for (int r = 0; r < pass.rays; ++r) {
    float w = imageLoad(uRays, ivec2(r, p)).w;
    if (w < 0.0f) {
      ++back;
      if (-w < nearestBack) {
        nearestBack = -w;
        backDir = probeRayDirection(r);
      }
    } else if (w < nearestFront) {
      nearestFront = w;
      frontDir = probeRayDirection(r);
    }
  }
  vec3 offset = probeStates[p].xyz;
  bool inside = 4 * back > pass.rays;
  if (pass.move != 0) {
    float least = 0.2f * min(pass.spacing.x, min(pass.spacing.y, pass.spacing.z));
    if (inside)
      offset += backDir * (nearestBack + 0.5f * least);
    else if (nearestFront < least)
      offset -= frontDir * (least - nearestFront);
    offset = clamp(offset, -0.45f * pass.spacing.xyz, 0.45f * pass.spacing.xyz);
  }
  probeStates[p] = vec4(offset, inside ? 0.0f : 1.0f);
}
