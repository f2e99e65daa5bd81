// Screen-space directional occlusion with one indirect bounce — Ritschel, Grosch, Seidel,
// "Approximating Dynamic Global Illumination in Image Space", I3D 2009, §3.1 (directional
// occlusion), §3.2 (the indirect bounce), §4 (interleaving and the geometry-aware blur: the gather
// kit's). One invocation per gather pixel: N cosine-distributed directions from the G-buffer point of
// the pixel's representative image texel, lifted `offset` pixels along the normal; what lies along
// them is read from the frame alone — the G-buffer (positions, normals) and the sample's direct light
// (the sender image: diffuse direct radiance of each visible surface, DirectPass with a sender target).
//
// A point X is occluded (shared/screen_space.glsl: screenOccluded) where it lies below the tangent
// plane of the surface the camera sees at X's pixel (for a point on that pixel's camera ray: behind
// it), within `thickness` behind it when that is set (0: the paper's test, a surface extends without
// limit behind what the camera sees).
//
// estimator = patch (the paper): direction i gets one point at a uniform distance λ·r; unoccluded, its
// direction reads the environment (§3.1); occluded, the surface at its pixel is a sender patch of area
// A_s = π r² / N facing along its normal, which adds L_s A_s cos θ_s cos θ_r / (π d²) (§3.2; the
// per-sample share clamped to 1/N, the paper clamps d: shared/screen_space.glsl, ssdoPatchShare).
// Not a consistent estimator of the near field: A_s is a heuristic and one point decides a whole
// direction.
// estimator = march: each direction is marched through `steps` points up to r (jittered) to the first
// occluded one; the surface there gives its radiance L_s to the direction if it faces it, nothing if
// the direction meets its back; a direction that meets nothing within r or leaves the screen reads the
// environment. Where every surface the rays meet is seen by the camera, this is the exact near-field
// integral (`reference integrator=nearfield`) up to the step size and the pixel grid.
//
// Output: rgb = mean radiance arriving along the directions (so the reflected indirect light of a
// diffuse surface is albedo × rgb), w = 1 where there is a surface, 0 elsewhere.
#include "shared/constants.glsl"
#include "shared/sampling.glsl"
#include "shared/brdf.glsl"
#include "shared/environment.glsl"
#include "shared/gpu_scene.glsl"
#include "shared/screen_space.glsl"
#define GATHER_DIRECTIONS
#include "illum/gather/gather_pass.glsl"
#include "params.glsl"

layout(rgba32f, binding = IMAGE_OUTPUT) uniform image2D uIndirect;
layout(binding = TEXUNIT_PASS_INPUT2) uniform sampler2D uSender;  // diffuse direct radiance, rgb

layout(std140, binding = UBO_PASS) uniform Pass { SsdoPassParams pass; };

ivec2 gatherSize() { return imageSize(uIndirect); }

void gatherEmpty(ivec2 q) { imageStore(uIndirect, q, vec4(0.0f)); }

// The image pixel X projects to (false: behind the camera or off the screen).
bool screenPixel(vec3 X, out ivec2 px) {
  mat4 m = mat4(pass.viewProj[0], pass.viewProj[1], pass.viewProj[2], pass.viewProj[3]);
  vec4 c = m * vec4(X, 1.0f);
  px = ivec2(0);
  if (!(c.w > 0.0f)) return false;
  vec2 ndc = c.xy / c.w;
  if (any(lessThan(ndc, vec2(-1.0f))) || any(greaterThanEqual(ndc, vec2(1.0f)))) return false;
  ivec2 size = textureSize(gPosition, 0);
  px = min(ivec2((ndc * 0.5f + 0.5f) * vec2(size)), size - 1);
  return true;
}

struct Sender {
  bool onScreen;  // X projects into the image, in front of the camera
  bool occluded;  // X lies behind the surface the camera sees at its pixel
  vec3 p, n;      // that surface
  ivec2 px;       // X's pixel
};

Sender occluder(vec3 X) {
  Sender s;
  s.occluded = false;
  s.p = vec3(0.0f);
  s.n = vec3(0.0f, 0.0f, 1.0f);
  s.onScreen = screenPixel(X, s.px);
  if (!s.onScreen) return s;
  vec4 P = texelFetch(gPosition, s.px, 0);
  if (P.w == 0.0f) return s;  // the sky
  s.p = P.xyz;
  s.n = normalize(texelFetch(gNormal, s.px, 0).xyz);  // faces the camera
  // A tenth of a pixel's world size there: below the plane by less is the plane itself. (A whole
  // pixel's shifted hits at grazing angles: indirect energy −4 % / +4 % by region at 64².)
  float eps = 0.1f * gather.camera.w * distance(P.xyz, gather.camera.xyz);
  s.occluded = screenOccluded(X, s.p, s.n, pass.forward.xyz, eps, pass.thickness);
  return s;
}

vec3 senderRadiance(Sender s) { return texelFetch(uSender, s.px, 0).xyz; }

void gatherPixel(ivec2 q, vec3 p, vec3 n) {
  Basis frame = makeBasis(n);
  float pixel = gather.camera.w * distance(p, gather.camera.xyz);
  vec3 origin = p + n * (pass.offset * pixel);
  float r = pass.radius;
  vec3 sum = vec3(0.0f);
  for (int i = gather.batchFirst; i < gather.batchEnd; ++i) {
    vec3 d = gatherDirection(q, i, frame);
    // This direction's jitter of its distances, shifted with the render's seed.
    float xi = fract(uintToUnitFloat(rngSeed(uint(q.x) | (uint(q.y) << 16u), uint(i), uint(gather.frame))) +
                     gather.rotation.x);
    if (pass.estimator == SSDO_PATCH) {
      vec3 X = origin + d * (max(xi, 1e-3f) * r);
      Sender s = occluder(X);
      if (!s.occluded) {
        if (pass.env != 0) sum += gpuEnvironmentRadiance(d);
        continue;
      }
      sum += senderRadiance(s) * ssdoPatchShare(p, n, s.p, s.n, r);
    } else {
      bool hit = false;
      for (int j = 0; j < pass.steps; ++j) {
        vec3 X = origin + d * (r * (float(j) + xi) / float(pass.steps));
        Sender s = occluder(X);
        if (!s.onScreen) break;  // the frustum is convex: the direction does not come back
        if (!s.occluded) continue;
        if (dot(s.n, d) < 0.0f) sum += senderRadiance(s);  // its front faces the direction
        hit = true;
        break;
      }
      // Off the screen the frame shows nothing: the environment, as past r.
      if (!hit && pass.env != 0) sum += gpuEnvironmentRadiance(d);
    }
  }
  imageStore(uIndirect, q, vec4(gatheredBefore(uIndirect, q).xyz + sum / float(gather.rays), 1.0f));
}
