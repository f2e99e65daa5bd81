// The temporal filter (illum/framework/temporal.h): this frame's mean (the film's sum over its samples)
// blended with the previous frames' filtered image reprojected to this frame.
//
// Reprojection moves the pixel by its surface's motion on screen: the G-buffer's world position
// through the previous frame's camera less through this one's, both without jitter (so a camera that
// stands still reads its history at the pixel itself, unfiltered), and keeps a history texel only where the previous G-buffer saw the same
// surface there: within planeTolerance pixel sizes of this pixel's tangent plane, its normal within
// normalCos and the same material (disocclusion, and an object that moved away, are rejected; the
// bilinear weights of the kept texels are renormalized). An object that moves keeps the history of the
// world point it covers now where that point looks the same (diffuse light is a function of position
// and normal, not of which object's surface is there), and what its motion changed in the light is
// held by clipping: the history is clamped to the current frame's 3×3 mean ± clampSigma·σ (variance
// clipping, Salvi 2016; the box widened to hold the current value), per channel. Then
// out = h + (c − h)·m / n with m = currentFrames (1 for an animation's frame) and n = the history's
// length + m, at most 1 / alpha (an exponential average from there), and out = c once m ≥ n: where
// nothing changed and the frames repeat their samples, out = c exactly, and the viewer's standing
// camera shows its own mean once it has 1 / alpha samples. w of the output holds n.
#include "shared/bindings.glsl"
#include "shared/gbuffer.glsl"
#include "params.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(std140, binding = UBO_PASS) uniform Pass { TemporalParams pass; };
layout(rgba32f, binding = IMAGE_TEMPORAL_SUM) uniform readonly image2D uSum;
layout(rgba32f, binding = IMAGE_TEMPORAL_HISTORY) uniform readonly image2D uHistory;
layout(rgba32f, binding = IMAGE_TEMPORAL_OUTPUT) uniform writeonly image2D uOut;
layout(binding = TEXUNIT_PASS_INPUT) uniform sampler2D uPreviousPosition;  // the previous G-buffer's
layout(binding = TEXUNIT_PASS_INPUT2) uniform sampler2D uPreviousNormal;

vec3 current(ivec2 px) { return imageLoad(uSum, px).xyz * pass.invSamples; }

// The blend of history h (its length in w) with the current mean c, and the new length in w.
vec4 blend(vec4 h, vec3 c) {
  float n = min(h.w + pass.currentFrames, 1.0f / pass.alpha);
  if (pass.currentFrames >= n) return vec4(c, n);
  return vec4(h.xyz + (c - h.xyz) * (pass.currentFrames / n), n);  // h = c gives c exactly
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(uOut);
  if (px.x >= size.x || px.y >= size.y) return;
  vec3 c = current(px);
  vec4 p = texelFetch(gPosition, px, 0);
  vec4 n = texelFetch(gNormal, px, 0);
  if (pass.hasHistory == 0) {  // the first frame: no history
    imageStore(uOut, px, blend(vec4(0.0f), c));
    return;
  }
  if (p.w == 0.0f) {
    // No surface at the pixel's centre (the background, or an edge whose jittered samples saw one):
    // its history is its own pixel's where the camera stood still and saw no surface there either.
    bool kept = pass.cameraStill != 0 && texelFetch(uPreviousPosition, px, 0).w == 0.0f;
    imageStore(uOut, px, blend(kept ? imageLoad(uHistory, px) : vec4(0.0f), c));
    return;
  }
  mat4 prev = mat4(pass.previousViewProj[0], pass.previousViewProj[1], pass.previousViewProj[2],
                   pass.previousViewProj[3]);
  mat4 now = mat4(pass.viewProj[0], pass.viewProj[1], pass.viewProj[2], pass.viewProj[3]);
  vec4 clip = prev * vec4(p.xyz, 1.0f), clipNow = now * vec4(p.xyz, 1.0f);
  float weight = 0.0f;
  vec4 history = vec4(0.0f);
  if (clip.w > 0.0f && clipNow.w > 0.0f) {
    vec2 motion = (clip.xy / clip.w - clipNow.xy / clipNow.w) * 0.5f * vec2(size);
    vec2 at = vec2(px) + motion;  // texel centres at integers
    ivec2 base = ivec2(floor(at));
    vec2 f = at - vec2(base);
    float tolerance = pass.planeTolerance * pass.eye.w * length(p.xyz - pass.eye.xyz);
    for (int j = 0; j < 4; ++j) {
      ivec2 q = base + ivec2(j & 1, j >> 1);
      if (q.x < 0 || q.y < 0 || q.x >= size.x || q.y >= size.y) continue;
      vec4 hp = texelFetch(uPreviousPosition, q, 0);
      vec4 hn = texelFetch(uPreviousNormal, q, 0);
      if (hp.w == 0.0f || hn.w != n.w) continue;  // no surface there, or another material
      if (abs(dot(hp.xyz - p.xyz, n.xyz)) > tolerance || dot(hn.xyz, n.xyz) < pass.normalCos) continue;
      float w = ((j & 1) != 0 ? f.x : 1.0f - f.x) * ((j >> 1) != 0 ? f.y : 1.0f - f.y);
      weight += w;
      history += w * imageLoad(uHistory, q);
    }
  }
  if (weight < 1e-3f) {  // disoccluded: this frame alone
    imageStore(uOut, px, blend(vec4(0.0f), c));
    return;
  }
  history /= weight;
  vec3 h = history.xyz;
  if (pass.clampSigma > 0.0f) {
    vec3 m1 = vec3(0.0f), m2 = vec3(0.0f);
    float count = 0.0f;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        ivec2 q = clamp(px + ivec2(dx, dy), ivec2(0), size - 1);
        vec3 v = current(q);
        m1 += v;
        m2 += v * v;
        count += 1.0f;
      }
    m1 /= count;
    vec3 sigma = sqrt(max(m2 / count - m1 * m1, vec3(0.0f)));
    // The box holds the current value itself: where nothing changed (h = c) nothing is clipped.
    h = clamp(h, min(m1 - pass.clampSigma * sigma, c), max(m1 + pass.clampSigma * sigma, c));
  }
  imageStore(uOut, px, blend(vec4(h, history.w), c));
}
