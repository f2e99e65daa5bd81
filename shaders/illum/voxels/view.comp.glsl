// `voxels` (illum/methods/voxels.cpp): the binary grid, or one OR-mip level,
// seen from the camera. Per pixel, the jittered camera ray (GL rows bottom-up,
// as the sample image) is traced with the chosen GLSL tracer through the
// pyramid from level pass.level up (pyramidFromLevel: that level's columns are
// its voxels); the face of the first set voxel (or column cell) it enters is
// coloured by its axis (x red, y green, z blue), shaded by |cos| to the ray,
// darkened with distance (from the scene's nearest to its farthest point) and
// outlined where the cell's edges are at least 4 pixels apart; a miss is black.
#include "shared/bindings.glsl"
#include "traverse/tracer.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
#include "params.glsl"
layout(rgba32f, binding = IMAGE_SAMPLE) uniform writeonly image2D uImage;
layout(std140, binding = UBO_PASS) uniform Pass { VoxelViewParams pass; };

vec3 cameraRay(vec2 ndc) {
  const mat4 invViewProj = mat4(pass.invViewProj[0], pass.invViewProj[1], pass.invViewProj[2], pass.invViewProj[3]);
  // Reversed-Z: depth 1 is the near plane; any smaller depth lies farther along the same ray.
  const vec4 a = invViewProj * vec4(ndc, 1.0f, 1.0f), b = invViewProj * vec4(ndc, 0.5f, 1.0f);
  return normalize(b.xyz / b.w - a.xyz / a.w);
}

void main() {
  const ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  const ivec2 size = imageSize(uImage);
  if (q.x >= size.x || q.y >= size.y) return;
  const vec2 ndc = (vec2(q) + 0.5f) / vec2(size) * 2.0f - 1.0f;
  const vec3 dir = cameraRay(ndc);
  const PyramidParams p = pyramidFromLevel(pyramidFromUniforms(), pass.level);
  const vec3 eye = pass.eye.xyz;
  const float t0 = pass.eye.w > 0.0f ? pass.eye.w / dot(dir, pass.forward.xyz) : 0.0f;
  TraceHit h = tracePyramid(p, eye + t0 * dir, dir, 1e30f);
  h.t += t0;
  vec3 c = vec3(0.0f);
  if (h.hit != 0u) {
    const GridParams g = p.grid;
    // The entered face: of the voxel's three entry planes (slab test in grid units), the last one
    // the ray crosses. (The hit point alone is ambiguous where a ray runs along a cell boundary.)
    const vec3 o = worldToGrid(g, eye), dg = worldToGrid(g, eye + dir) - o;
    vec3 entry;
    for (int i = 0; i < 3; ++i) {
      const float plane = float(h.voxel[i]) + (dg[i] > 0.0f ? 0.0f : 1.0f);
      entry[i] = abs(dg[i]) > 1e-12f ? (plane - o[i]) / dg[i] : -1e30f;
    }
    const int axis = entry.x >= entry.y && entry.x >= entry.z ? 0 : (entry.y >= entry.z ? 1 : 2);
    const vec3 n = axis == 0 ? g.axisX.xyz : (axis == 1 ? g.axisY.xyz : g.axisZ.xyz);
    const vec3 base = axis == 0 ? vec3(0.9f, 0.42f, 0.38f) : (axis == 1 ? vec3(0.45f, 0.85f, 0.45f) : vec3(0.42f, 0.55f, 0.95f));
    const float cue = clamp((h.t - pass.nearest) / max(pass.farthest - pass.nearest, 1e-30f), 0.0f, 1.0f);
    c = base * (0.3f + 0.7f * abs(dot(n, dir))) * mix(1.0f, 0.4f, cue);
    // The cell's edges on the entered face, about one pixel wide, where a cell spans 4 pixels or
    // more: the grid coordinates per pixel come from the neighbouring pixels' rays meeting the
    // face's plane (so faces seen at a grazing angle get no edges that would alias).
    const float plane = float(h.voxel[axis]) + (dg[axis] > 0.0f ? 0.0f : 1.0f);
    const vec3 at = o + dg * entry[axis];
    const vec3 dx = worldToGrid(g, eye + cameraRay(ndc + vec2(2.0f / float(size.x), 0.0f))) - o;
    const vec3 dy = worldToGrid(g, eye + cameraRay(ndc + vec2(0.0f, 2.0f / float(size.y)))) - o;
    const vec3 ax = o + dx * ((plane - o[axis]) / dx[axis]), ay = o + dy * ((plane - o[axis]) / dy[axis]);
    float edge = 1.0f;
    for (int i = 0; i < 3; ++i) {
      if (i == axis) continue;
      const float perPixel = max(abs(ax[i] - at[i]), abs(ay[i] - at[i]));  // cells per pixel
      const float f = at[i] - float(h.voxel[i]);
      // Faded in from cells of 4 pixels to cells of 8, so the lines do not flicker into dots.
      if (min(f, 1.0f - f) < perPixel) edge = min(edge, mix(1.0f, 0.55f, smoothstep(0.25f, 0.125f, perPixel)));
    }
    c *= edge;
  }
  imageStore(uImage, q, vec4(c, 1.0f));
}
