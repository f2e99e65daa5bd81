// The shared layer of the voxel cone-tracing modules (vct, vct_ao; the cone
// march is shaders/illum/vct/cones.glsl): the pre-integrated radiance /
// opacity volume, and the cone constellations with their weights.
//
// The volume (voxelize/value_textures: the radiance channel, premultiplied
// (L·α, α), with an isotropic or six-direction anisotropic mip chain) is
// filled in one of three ways (`radiance`):
//   inject  the three-axis conservative rasterization lights each (triangle,
//           cell) pair with the direct pass' shadow-mapped diffuse light
//           (shaders/illum/vct/inject.frag; Dinse 2015 §3.1); the opacity is
//           the binary grid of the `voxelizer` parameter (any of the registry;
//           default conservative, the thesis' own voxelization);
//   atlas   the atlas voxelizer's multi-valued radiance channel (VGI §3), its
//           points' cells the opacity (voxelizer atlas);
//   none    opacity only (vct_ao), from the binary grid.
#pragma once
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/gl_handles.h"
#include "illum/direct.h"
#include "illum/scene_resources.h"

namespace vgi {

class Frame;
class ParamSet;
class ShaderLibrary;
class ValueTextures;

struct ConeVolumeSettings {
  BinaryGridNeed grid;
  std::string radiance = "inject";  // inject | atlas | none
  bool anisotropic = true;
  bool absWeights = true;  // the faces mixed by |d| (the thesis) or d²
  float step = 1.0f;       // the march's step, in cone diameters
  ShadowParams shadow;     // the light maps' (injection and direct light)
};
// Reads voxels, voxelizer, anisotropic, face_weights, step and (withRadiance) radiance.
ConeVolumeSettings readConeVolumeParams(ParamSet& params, bool withRadiance, bool anisotropicDefault,
                                        bool absWeightsDefault, float stepDefault);
// What a cone module needs besides the G-buffer: light maps, the binary grid
// and its pyramid, and with radiance=atlas the value grids.
void addConeVolumeNeeds(SceneNeeds& needs, const ConeVolumeSettings& s);

class ConeVolume {
 public:
  // Once per frame (prepareFrame): the scene may have moved.
  void invalidate() { dirty_ = true; }
  // Before each sample: (re)builds the volume after invalidate() or when the
  // light maps were drawn again (area lights: per sample), timed as
  // "vct_inject_max", "vct_inject" and the resolve's "value_resolve", "value_mips".
  void update(Frame& frame, const ConeVolumeSettings& s);
  // Binds the textures and sets cones.glsl's uniforms on `program` (in use).
  void bind(Frame& frame, ShaderLibrary& shaders, unsigned program) const;
  // The program defines of cones.glsl for these settings.
  static void addDefines(const ConeVolumeSettings& s, std::map<std::string, std::string>& defines);
  const ValueTextures& textures(const Frame& frame) const;
  nlohmann::json stats() const { return stats_; }
  float voxelSize() const { return voxel_; }

 private:
  void inject(Frame& frame);
  ConeVolumeSettings s_;
  std::unique_ptr<ValueTextures> own_;
  GlBuffer counts_, sums_, max_;
  unsigned prog_ = 0, maxProg_ = 0;
  uint64_t renders_ = ~uint64_t(0);
  bool dirty_ = true;
  float radianceMax_ = 1.0f, voxel_ = 0.0f;
  nlohmann::json stats_ = nlohmann::json::object();
};

// Cones traced one by one through a volume (tests): apex, unit direction,
// tan of the half-angle, length; per cone its radiance + opacity and
// (occlusion, escaped, samples, 0). mediumAlpha ≥ 0: a uniform medium of that
// opacity per voxel instead of the volume (the closed-form test).
struct ProbeCone {
  glm::vec3 apex, dir;
  float tanHalf, length;
};
struct ProbeResult {
  glm::vec4 radianceOpacity, occlusionEscapedSamples;
};
std::vector<ProbeResult> traceConesGl(const ValueTextures& volume, ShaderLibrary& shaders,
                                      const std::vector<ProbeCone>& cones, float step, bool skipEmpty,
                                      float mediumAlpha = -1.0f);

// A cone constellation in the tangent frame (z = the normal): axes xyz and, in
// w, each axis' share of the cosine-weighted hemisphere (the directions
// nearer to it than to any other axis, by quadrature; Σ w = 1, so the cones'
// weights W_k = π w sum to π, Dinse 2015 §3.3).
std::vector<glm::vec4> coneWeights(const std::vector<glm::vec3>& axes);
// `centre` (one axis along the normal) plus `ring` axes at polar angle
// ringPolarDeg, the first along the tangent.
std::vector<glm::vec4> ringConstellation(bool centre, int ring, float ringPolarDeg);

}  // namespace vgi
