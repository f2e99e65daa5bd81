// VGI §5.1 near-field gathering, one invocation per indirect-buffer pixel:
// N cosine-distributed rays from the G-buffer point of the pixel's
// representative full-resolution texel, started `uOffset` world units along
// the normal (a voxel diagonal by default: every cell the local plane touches
// lies within one diagonal of it, so the ray cannot hit its own surface),
// traced through the binary voxel grid up to the radius r; a hit is
// back-projected into every reflective shadow map and receives the stored
// radiance where the RSM sees the same surface (the ε rule); rays that leave r
// read the environment (directional occlusion) when uEnv is set.
//
// Interleaved sampling (Keller and Heidrich 2001): the pixels of a k×k block
// use k² different sets of N directions, which together stratify the
// hemisphere (Hammersley over k²·N points, rotated per frame); the
// geometry-aware blur afterwards averages them.
//
// Output: rgb = mean radiance arriving along the rays (so the reflected
// indirect light of a diffuse surface is albedo × rgb), w = 1 where there is a
// surface, 0 elsewhere.
#include "../../shared/constants.glsl"
#include "../../shared/sampling.glsl"
#include "../../shared/brdf.glsl"
#include "../../shared/environment.glsl"
#include "../../shared/gpu_scene.glsl"
#include "../../shared/light_maps.glsl"
#include "../../traverse/tracer.glsl"
#include "indirect_buffer.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform writeonly image2D uIndirect;

uniform int uRays;           // N
uniform int uInterleave;     // k
uniform float uRadius;       // r, world units
uniform float uOffset;       // start offset along the normal, world units
uniform float uVoxelDiagonal;
uniform int uEnv;
uniform vec2 uRotation;      // per-frame Cranley–Patterson rotation
uniform int uRsmRes;


// Direct radiance leaving the hit point y, read back from every RSM.
vec3 backProject(vec3 y) {
  vec3 sum = vec3(0.0f);
  for (int l = 0; l < lights.length(); ++l) {
    int f = lightFaceOf(l, y);
    LightFace face = lightFaces[f];
    vec2 uv = lightMapUv(face, y);
    if (uv.x < 0.0f || uv.y < 0.0f || uv.x > 1.0f || uv.y > 1.0f) continue;
    ivec3 texel = ivec3(min(ivec2(uv * float(uRsmRes)), ivec2(uRsmRes - 1)), f);
    vec4 P = texelFetch(lightPosition, texel, 0);
    if (P.w == 0.0f) continue;
    vec3 n = texelFetch(lightNormal, texel, 0).xyz;
    LightSample ls = sampleDeltaLight(lights[l], P.xyz);
    float eps = backProjectionEpsilon(uVoxelDiagonal, lightMapTexelWorld(face, lightMapDistance(face, P.xyz)),
                                      dot(n, ls.wi));
    if (distance(y, P.xyz) < eps) sum += texelFetch(lightRadiance, texel, 0).xyz;
  }
  return sum;
}

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(uIndirect);
  if (q.x >= size.x || q.y >= size.y) return;
  ivec2 px = representative(q, textureSize(gPosition, 0));
  vec4 P = texelFetch(gPosition, px, 0);
  if (P.w == 0.0f) {
    imageStore(uIndirect, q, vec4(0.0f));
    return;
  }
  vec3 n = normalize(texelFetch(gNormal, px, 0).xyz);
  Basis frame = makeBasis(n);
  vec3 origin = P.xyz + n * uOffset;
  uint set = uint(q.x % uInterleave + uInterleave * (q.y % uInterleave));
  vec3 sum = vec3(0.0f);
  for (int r = 0; r < uRays; ++r) {
    // Every set alone spans the hemisphere (shared/sampling.glsl), so a blur
    // window that loses some sets at an edge loses samples, not azimuths.
    vec2 u = fract(interleavedSample(uint(r), set, uint(uRays), uint(uInterleave * uInterleave)) + uRotation);
    vec3 d = basisToWorld(frame, cosineSampleHemisphere(u));
    TraceHit h = traceRay(origin, d, uRadius);
    if (h.hit != 0u) sum += backProject(origin + h.t * d);
    else if (uEnv != 0) sum += gpuEnvironmentRadiance(d);
  }
  imageStore(uIndirect, q, vec4(sum / float(uRays), 1.0f));
}
