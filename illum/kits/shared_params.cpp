#include "illum/kits/shared_params.h"

#include "core/params.h"
#include "shaders/illum/voxel_hit_params.glsl"

namespace vgi {

void readShadowParams(ParamSet& p, ShadowParams& s) {
  s.resolution = p.getInt("shadow_res", 1024, "shadow map size (per face)", 16, 8192);
  s.bias = p.getFloat("shadow_bias", 1.0f,
                      "depth bias in shadow-map texels (receiver plane at the texel centre; slope-scaled "
                      "within 0.6 deg of grazing)",
                      0.0f, 100.0f);
  s.normalOffset =
      p.getFloat("normal_offset", 0.0f, "lookup offset along the normal, in texels", 0.0f, 100.0f);
}

float readOffset(ParamSet& p, float def, const std::string& why) {
  const std::string doc =
      "start offset of the rays or cones along the normal, in voxel diagonals: the guard against the "
      "receiver's own voxels" +
      (why.empty() ? std::string() : " (" + why + ")");
  return p.getFloat("offset", def, doc, 0.0f, 100.0f);
}

bool readEnv(ParamSet& p) {
  return p.getBool("env", true,
                   "what leaves the grid (nearfield: the radius) reads the scene's environment; a scene "
                   "without one has a black environment, so true adds nothing there");
}

bool readPassThrough(ParamSet& p, const std::string& rule) {
  return p.getBool("passthrough", true,
                   "rays go on past a hit that may be the start's own voxel (within a voxel diagonal of its "
                   "tangent plane) when " +
                       rule);
}

TemporalSettings readTemporal(ParamSet& p, const TemporalSettings& d) {
  TemporalSettings t;
  t.on =
      p.getBool("temporal", d.on,
                "the frames of an animation (--frames) are filtered over time: each frame is blended with "
                "the previous frames' filtered image, reprojected through the G-buffer (history kept where "
                "the previous frame saw the same surface, clipped to the current frame's neighbourhood); "
                "a still is not changed");
  t.alpha = p.getFloat("temporal_alpha", d.alpha,
                       "the least weight of the current frame: the history holds at most 1/alpha frames",
                       0.01f, 1.0f);
  t.clampSigma = p.getFloat("temporal_clamp", d.clampSigma,
                            "the history is clipped to the current frame's 3x3 mean +- this many standard "
                            "deviations (0: not clipped)",
                            0.0f, 100.0f);
  t.continueSamples =
      p.getString("temporal_samples", d.continueSamples ? "continue" : "repeat",
                  "with temporal: repeat (every frame takes the same samples, so where nothing changes the "
                  "frames are equal) or continue (frame f takes samples f*spp...: the history adds samples, "
                  "lower error where nothing changes but each frame's new noise flickers)",
                  {"repeat", "continue"}) == "continue";
  return t;
}

int readBackProjection(ParamSet& p) {
  const std::string b =
      p.getString("backprojection", "plane",
                  "hit -> RSM: plane (the ray meets the plane of the surface the RSM sees "
                  "there) or entry (VGI: the voxel entry point, epsilon >= a voxel diagonal)",
                  {"plane", "entry"});
  return b == "entry" ? shared::BACK_PROJECTION_ENTRY : shared::BACK_PROJECTION_PLANE;
}

}  // namespace vgi
