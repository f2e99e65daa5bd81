// DDGI's probe update (Majercik et al. 2019, §4): one invocation per texel of the irradiance atlas
// (or, with DDGI_DISTANCE, of the distance atlas). A texel of probe p's tile stands for a direction
// (its interior texel's: the border repeats the interior across the octahedral map's folds,
// shared/octahedral.glsl); its new value is the mean of the probe's rays weighted by max(0, cos) —
// the cosine-weighted mean radiance, E / π — or, for distances, by max(0, cos)^50 — the mean distance
// and its square (the moments of the Chebyshev test; a back face's distance counts a fifth) — blended
// with the old value by the hysteresis.
#include "shared/bindings.glsl"
#include "shared/constants.glsl"
#include "shared/octahedral.glsl"
#include "params.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std140, binding = UBO_PASS) uniform Pass { DdgiParams pass; };
#ifdef DDGI_DISTANCE
layout(rg32f, binding = IMAGE_OUTPUT) uniform image2D uAtlas;
const int kTile = DDGI_DISTANCE_TILE;
#else
layout(rgba32f, binding = IMAGE_OUTPUT) uniform image2D uAtlas;
const int kTile = DDGI_IRRADIANCE_TILE;
#endif
layout(rgba32f, binding = IMAGE_OUTPUT2) uniform readonly image2D uRays;
#include "rays.glsl"

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(q, imageSize(uAtlas)))) return;
  ivec2 tile = q / kTile;
  int p = tile.x + tile.y * pass.counts.w;
  if (p >= pass.counts.x * pass.counts.y * pass.counts.z) return;
  vec3 dir = octTexelDirection(q - tile * kTile, kTile);
  vec3 sum = vec3(0.0f);
  float total = 0.0f;
  for (int r = 0; r < pass.rays; ++r) {
    vec4 ray = imageLoad(uRays, ivec2(r, p));
    float w = max(0.0f, dot(dir, probeRayDirection(r)));
#ifdef DDGI_DISTANCE
    w = pow(w, 50.0f);
    float d = ray.w < 0.0f ? -0.2f * ray.w : ray.w;  // a back face: a fifth of its distance
    sum += w * vec3(d, d * d, 0.0f);
#else
    sum += w * ray.xyz;
#endif
    total += w;
  }
  vec4 value = vec4(total > 0.0f ? sum / total : vec3(0.0f), 0.0f);
  vec4 old = imageLoad(uAtlas, q);
  imageStore(uAtlas, q, mix(value, old, pass.hysteresis));
}
