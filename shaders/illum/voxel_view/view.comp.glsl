// `voxels` (illum/voxel_view.cpp): the binary grid seen from the camera.
// Per pixel, the jittered camera ray (GL rows bottom-up, as the sample
// image) is traced through the OR-mip pyramid with the chosen GLSL tracer;
// the face of the first set voxel it enters is coloured by its axis
// (x red, y green, z blue), shaded by |cos| to the ray and darkened with
// distance (over one scene diagonal); a miss is black.
#include "../../shared/bindings.glsl"
#include "../../traverse/tracer.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = IMAGE_SAMPLE) uniform writeonly image2D uImage;
uniform mat4 uInvViewProj;
uniform vec3 uEye;
uniform float uInvDiagonal;  // depth cue: darker with distance, over one scene diagonal

void main() {
  const ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  const ivec2 size = imageSize(uImage);
  if (q.x >= size.x || q.y >= size.y) return;
  const vec2 ndc = (vec2(q) + 0.5f) / vec2(size) * 2.0f - 1.0f;
  // Reversed-Z: depth 1 is the near plane; any smaller depth lies farther along the same ray.
  const vec4 a = uInvViewProj * vec4(ndc, 1.0f, 1.0f), b = uInvViewProj * vec4(ndc, 0.5f, 1.0f);
  const vec3 dir = normalize(b.xyz / b.w - a.xyz / a.w);
  const TraceHit h = traceRay(uEye, dir, 1e30f);
  vec3 c = vec3(0.0f);
  if (h.hit != 0u) {
    const GridParams g = gridFromUniforms();
    // The entered face: of the voxel's three entry planes (slab test in grid units), the last one
    // the ray crosses. (The hit point alone is ambiguous where a ray runs along a cell boundary.)
    const vec3 o = worldToGrid(g, uEye), dg = worldToGrid(g, uEye + dir) - o;
    vec3 entry;
    for (int i = 0; i < 3; ++i) {
      const float plane = float(h.voxel[i]) + (dg[i] > 0.0f ? 0.0f : 1.0f);
      entry[i] = abs(dg[i]) > 1e-12f ? (plane - o[i]) / dg[i] : -1e30f;
    }
    const int axis = entry.x >= entry.y && entry.x >= entry.z ? 0 : (entry.y >= entry.z ? 1 : 2);
    const vec3 n = axis == 0 ? g.axisX.xyz : (axis == 1 ? g.axisY.xyz : g.axisZ.xyz);
    const vec3 base = axis == 0 ? vec3(0.9f, 0.42f, 0.38f) : (axis == 1 ? vec3(0.45f, 0.85f, 0.45f) : vec3(0.42f, 0.55f, 0.95f));
    c = base * (0.3f + 0.7f * abs(dot(n, dir))) * mix(1.0f, 0.35f, clamp(h.t * uInvDiagonal, 0.0f, 1.0f));
  }
  imageStore(uImage, q, vec4(c, 1.0f));
}
