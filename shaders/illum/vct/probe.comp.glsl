// Cones traced one per invocation (tests, `vgi` tools): cone i of the input
// buffer (apex xyz + tan θ, direction xyz + length) through the bound volume
// with cones.glsl's traceCone; out: radiance rgb + opacity, occlusion,
// escaped, samples. UNIFORM_MEDIUM: coneSample is a medium of opacity
// uMediumAlpha per voxel (a level-l cell: 1 − (1 − α)^(2^l), what the
// anisotropic chain composes for a uniform medium), for the closed form.
#ifdef UNIFORM_MEDIUM
#define CONE_SAMPLE
uniform float uMediumAlpha;
vec4 coneSample(vec3 q, vec3 d, float lod) {
  return vec4(0.0f, 0.0f, 0.0f, 1.0f - pow(1.0f - uMediumAlpha, exp2(lod)));
}
#endif
#include "cones.glsl"
layout(local_size_x = 64) in;
struct ProbeCone {
  vec4 apexTan;
  vec4 dirLength;
};
struct ProbeResult {
  vec4 radianceOpacity;
  vec4 occlusionEscapedSamples;
};
layout(std430, binding = BINDING_TRACE_RAYS) readonly buffer Cones { ProbeCone probeCones[]; };
layout(std430, binding = BINDING_TRACE_HITS) writeonly buffer Results { ProbeResult probeResults[]; };
uniform uint uCount;
uniform int uSkipEmpty;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uCount) return;
  ProbeCone c = probeCones[i];
  vec3 d = normalize(vec3(c.dirLength.x, c.dirLength.y, c.dirLength.z));
  ConeResult r = traceCone(vec3(c.apexTan.x, c.apexTan.y, c.apexTan.z), d, c.apexTan.w, c.dirLength.w,
                           c.dirLength.w, 0.0f, uSkipEmpty != 0, 0.0f, -1.0f);
  ProbeResult o;
  o.radianceOpacity = vec4(r.radiance, r.opacity);
  o.occlusionEscapedSamples = vec4(r.occlusion, r.escaped, float(r.samples), 0.0f);
  probeResults[i] = o;
}
