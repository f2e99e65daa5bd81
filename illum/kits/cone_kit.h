// The shared layer of the voxel cone-tracing modules (vct, vct_ao; the cone
// march is shaders/illum/vct/cones.glsl): their volume's parameters (the
// volume itself is the resource kind "cone_volume",
// illum/resources/cone_volume.h), and the cone constellations with their weights.
#pragma once
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "illum/kits/shared_params.h"
#include "illum/resources/cone_volume.h"
#include "illum/resources/sparse_octree.h"

namespace vgi {

class ParamSet;
class ShaderLibrary;
class ValueTextures;

struct ConeVolumeSettings {
  BinaryGridNeed grid;
  ConeRadiance radiance = ConeRadiance::Inject;
  enum class Storage { Dense, Svo } volume = Storage::Dense;  // dense (cone_volume) | svo (sparse_octree)
  bool anisotropic = true;
  bool directional = false;       // level-0 radiance seen from the cone's side (ConeVolumeNeed::directional)
  bool directionalChain = false;  // … in the anisotropic chain's first level too
  bool dilate = true;             // svo: allocate the nodes a neighbour's brick stencil needs
  int updateEvery = 1;            // svo: rebuild the tree at every k-th changed grid
  bool absWeights = true;         // the faces mixed by |d| (the thesis) or d²
  float step = 1.0f;              // the march's step, in cone diameters
  int maxLevel = -1;              // the highest mip level a cone samples (-1: the chain's last)
  int injectSmall = 27;           // inject: triangles of at most this many cells lit triangle-parallel
  ShadowParams shadow;            // the light maps' (injection and direct light)
  // The dense volume these settings build (radiance none: no light maps).
  ConeVolumeNeed need() const;
  // The sparse octree they build (volume=svo).
  SparseOctreeNeed octreeNeed() const;
  // Declares the volume (dense or svo), which a method then reads as get<ConeSource>().
  void addNeed(SceneNeeds& needs) const;
  // The program defines of cones.glsl for these settings.
  void addDefines(std::map<std::string, std::string>& defines) const;
};
// Reads voxels, voxelizer, volume, dilate, update_every, anisotropic,
// face_weights, step, max_level and (withRadiance) radiance, directional and inject_small.
ConeVolumeSettings readConeVolumeParams(ParamSet& params, bool withRadiance, bool anisotropicDefault,
                                        bool absWeightsDefault, float stepDefault);

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
// The same through a sparse octree (CONE_SVO: the same march, the octree's coneSample).
std::vector<ProbeResult> traceConesGl(const SparseVoxelOctree& octree, ShaderLibrary& shaders,
                                      const std::vector<ProbeCone>& cones, float step, bool skipEmpty);

// A cone constellation in the tangent frame (z = the normal): axes xyz and, in
// w, each axis' share of the cosine-weighted hemisphere (the directions
// nearer to it than to any other axis, by quadrature; Σ w = 1, so the cones'
// weights W_k = π w sum to π, Dinse 2015 §3.3).
std::vector<glm::vec4> coneWeights(const std::vector<glm::vec3>& axes);
// `centre` (one axis along the normal) plus `ring` axes at polar angle
// ringPolarDeg, the first along the tangent.
std::vector<glm::vec4> ringConstellation(bool centre, int ring, float ringPolarDeg);

}  // namespace vgi
