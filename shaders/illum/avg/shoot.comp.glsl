// AVG light tracing (Bashford-Rogers et al. 2011, §III-B), one invocation per
// VPL chain i < uChains: a ray from a light — lights chosen in proportion to
// their emitted power (stratified over the chains), the ray distributed as
// the light emits (shared/vpl.glsl: sampleLightRay) from the chain's point of
// the R2 sequence, rotated per sample only: the same VPLs in every frame of
// an animation (the paper's answer to flicker) — carrying Φ_total / N, is
// ray-marched through the AVG (steps of uStep) until it enters a cell that
// holds triangles (other than the one it starts in, and passing the cells of
// the surface it starts on: march()). The VPL is pushed a
// random distance (up to half a cell) further into that cell, takes the
// cell's mean normal made to face the ray (shared/avg.glsl: avgVplNormal) and carries the ray's flux
// times the cell's mean albedo (what it reflects). The next ray leaves it
// cosine-distributed from a voxel diagonal along the normal; Russian roulette
// on the mean reflectance after every VPL, up to uBounces VPLs per chain.
#include "shared/constants.glsl"
#include "shared/sampling.glsl"
#include "shared/brdf.glsl"
#include "shared/environment.glsl"
#include "shared/gpu_scene.glsl"
#include "shared/vpl.glsl"
#include "shared/avg.glsl"
#include "voxelize/grid_uniforms.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = BINDING_AVG) readonly buffer AvgCells { uint avgCells[]; };
layout(std430, binding = BINDING_VPLS) writeonly buffer Vpls { Vpl vpls[]; };
uniform uint uChains;
uniform int uBounces;
uniform float uStep;          // march step, world units
uniform float uCellDiagonal;  // of an AVG cell, world units
uniform float uMaxDistance;   // longer than any ray through the grid
uniform vec3 uCentre;         // the scene's bounding sphere (directional lights)
uniform float uRadius;
uniform uvec2 uRotation;
uniform uint uSeed;
uniform uint uSampleIndex;

float lightPower(uint l) { return lightEmittedPower(lights[l], uRadius); }

// The first cell with triangles along (o, d) past the start cell; false if none within the grid.
bool march(vec3 o, vec3 d, out ivec3 cell, out float t) {
  GridParams g = gridFromUniforms();
  ivec3 res = ivec3(uResolution.xyz);
  ivec3 start = ivec3(floor(worldToGrid(g, o)));
  bool entered = false;  // a ray from outside the grid marches until it enters it
  for (t = 0.0f; t < uMaxDistance; t += uStep) {
    ivec3 c = ivec3(floor(worldToGrid(g, o + t * d)));
    bool inside = all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, res));
    if (!inside) {
      if (entered) return false;
      continue;
    }
    entered = true;
    if (c == start) continue;
    uint base = avgCellBase(uvec3(c), uvec3(res));
    uint n = avgCells[base + 6u];
    if (n == 0u) continue;
    // The own-band pass: a cell whose surface plane (its mean normal through
    // its centre) lies within a cell diagonal of the ray's origin is the
    // surface the ray starts on (a VPL's own wall) or next to (a light under
    // the ceiling): at 64³, rays leaving such a point at up to ~45° to the
    // surface run through its cells and stopped there, piling VPLs around
    // the origin. Passed, they go on to what they would meet.
    vec3 ns = avgMean(ivec3(int(avgCells[base]), int(avgCells[base + 1u]), int(avgCells[base + 2u])), n);
    vec3 centre = gridToWorld(g, vec3(c) + 0.5f);
    if (length(ns) > 0.5f && abs(dot(normalize(ns), o - centre)) < uCellDiagonal) continue;
    cell = c;
    return true;
  }
  return false;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uChains) return;
  int b = 0;
  uint count = uint(uLightCount);
  float total = 0.0f;
  for (uint l = 0u; l < count; ++l) total += lightPower(l);
  if (total > 0.0f) {
    // The light: the chain's stratum of the power distribution.
    float x = (float(i) + 0.5f) / float(uChains) * total;
    uint l = 0u;
    for (; l + 1u < count; ++l) {
      if (x < lightPower(l)) break;
      x -= lightPower(l);
    }
    vec2 u = r2Point(i, uRotation.x, uRotation.y);
    uint rng = rngSeed(i, uSampleIndex, uSeed ^ 0x2545f491u);
    vec2 v = vec2(rngNext(rng), rngNext(rng));
    LightRay ray = sampleLightRay(lights[l], u, v, uCentre, uRadius);
    vec3 I = lights[l].intensityFalloff.xyz;
    // Φ_l / (N p_l) with p_l = power_l / total: the light's colour at Φ_total / N.
    vec3 beta = I / max((I.x + I.y + I.z) / 3.0f, 1e-30f) * (total / float(uChains));
    vec3 o = ray.origin, d = ray.dir;
    GridParams g = gridFromUniforms();
    uvec3 res = uResolution.xyz;
    for (; b < uBounces; ++b) {
      ivec3 cell;
      float t;
      if (!march(o, d, cell, t)) break;
      uint base = avgCellBase(uvec3(cell), res);
      uint n = avgCells[base + 6u];
      vec3 nsum = avgMean(ivec3(int(avgCells[base]), int(avgCells[base + 1u]), int(avgCells[base + 2u])), n);
      vec3 albedo = avgMean(ivec3(uvec3(avgCells[base + 3u], avgCells[base + 4u], avgCells[base + 5u])), n);
      vec3 normal = avgVplNormal(nsum, d);
      vec3 p = o + d * (t + rngNext(rng) * 0.5f * length(g.axisX.xyz) / g.axisX.w);
      Vpl vpl;
      vpl.position = vec4(p, 1.0f);
      vpl.normal = vec4(normal, 0.0f);
      vpl.flux = vec4(beta * albedo, 0.0f);
      vpl.origin = uvec4(uvec3(cell), uint(b));
      vpls[uint(b) * uChains + i] = vpl;
      // Russian roulette on the mean reflectance, then a cosine-distributed bounce.
      float q = (albedo.x + albedo.y + albedo.z) / 3.0f;
      if (b + 1 < uBounces && !(rngNext(rng) < q)) {
        ++b;
        break;
      }
      beta *= albedo / max(q, 1e-30f);
      o = p + normal * uCellDiagonal;
      d = basisToWorld(makeBasis(normal), cosineSampleHemisphere(vec2(rngNext(rng), rngNext(rng))));
    }
  }
  for (; b < uBounces; ++b) vpls[uint(b) * uChains + i] = vplEmpty();
}
