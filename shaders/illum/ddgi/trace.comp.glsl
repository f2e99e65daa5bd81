// DDGI's probe rays (Majercik et al. 2019, §4; illum/methods/ddgi.cpp): one invocation per ray of a
// probe. Each update, every probe traces `rays` directions — spherical Fibonacci points under this
// update's random rotation — from its centre through the chosen tracer (voxels, or triangles with
// tracer=bvh; the hit in the cell that holds it, the hit vertex from the value grids as voxelpath's).
// A hit's radiance towards the probe is its direct light (RSM back-projection: diffuse, emission
// included as the emitters' lights) plus albedo × the field's E / π there (the last update's probes:
// each update adds a bounce); a ray that meets nothing reads the environment (with env).
//
// With pass.relocate, a hit on a back face — the hit cell's mean normal faces along the ray: the ray
// left a solid through its surface, so the probe is inside — gives no light and is marked by a
// negative distance (the relocation pass counts them; the distance update stores a fifth of it, so the
// probe sees a close occluder in that direction and the Chebyshev test shuts it out there).
//
// Output (x = ray, y = probe): rgb the radiance, w the distance to the hit (the longest stored
// distance, pass.spacing.w, where there is none; negative for a back face).
#include "shared/constants.glsl"
#include "shared/sampling.glsl"
#include "shared/brdf.glsl"
#include "shared/environment.glsl"
#include "shared/gpu_scene.glsl"
#include "shared/light_maps.glsl"
#include "shared/value_textures.glsl"
#include "traverse/tracer.glsl"
#include "illum/voxel_hits.glsl"
#include "params.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std140, binding = UBO_PASS) uniform Pass { DdgiParams pass; };
#include "probes.glsl"
#include "rays.glsl"
layout(rgba32f, binding = IMAGE_OUTPUT) uniform writeonly image2D uRays;

// Ray r's direction of this update.

void main() {
  int r = int(gl_GlobalInvocationID.x), p = int(gl_GlobalInvocationID.y);
  ivec3 c = pass.counts.xyz;
  if (r >= pass.rays || p >= c.x * c.y * c.z) return;
  vec3 o = probePosition(ivec3(p % c.x, (p / c.x) % c.y, p / (c.x * c.y)));
  vec3 d = probeRayDirection(r);
  vec3 L = vec3(0.0f);
  float dist = pass.spacing.w;
  float t;
  uvec3 voxel;
  BackProjection b;
  if (trace(o, d, d, t, voxel, b)) {  // (no pass-through: a probe has no surface of its own)
    dist = min(t, pass.spacing.w);
    bool back = pass.relocate != 0 && dot(texelFetch(valueNormal, ivec3(voxel), 0).xyz, d) > 0.0f;
    Vertex y;
    if (back)
      dist = -dist;
    else if (hitVertex(o, d, t, voxel, y))
      L = b.radiance + y.brdf.albedo * probeIrradiance(y.p, y.n, -d);
  } else if (pass.env != 0) {
    L = gpuEnvironmentRadiance(d);
  }
  imageStore(uRays, ivec2(r, p), vec4(L, dist));
}
