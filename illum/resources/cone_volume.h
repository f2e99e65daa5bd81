// Resource kind "cone_volume": the pre-integrated radiance / opacity volume
// that the voxel cone tracers march (vct, vct_ao; shaders/illum/vct/cones.glsl):
// the radiance channel of voxelize/value_textures, premultiplied (L·α, α),
// with an isotropic or six-direction anisotropic mip chain. Filled in one of
// three ways (`radiance`):
//   inject  the three-axis conservative rasterization lights each (triangle,
//           cell) pair with the light maps' shadow-tested diffuse light
//           (shaders/illum/vct/inject.frag; Dinse 2015 §3.1), the opacity
//           the binary grid of any voxelizer (through its pyramid's words);
//           injected again whenever the light maps are drawn again — where
//           only dynamic meshes moved, only the cells they and their shadow
//           covered before and after (changedCells) are injected, resolved
//           and filtered again, the range from the cells' kept maxima;
//   texels  the 2013 article's: each texel of the (reflective) light maps
//           into the cell its surface point falls in (inject_texels.comp);
//           cells no texel reaches stay unlit (its holes);
//   atlas   the atlas voxelizer's radiance channel (VGI §3): the value grids
//           are the volume (nothing of its own is allocated);
//   none    opacity only (vct_ao), from the binary grid.
// `directional` (inject only; ours): the injection also sums the direction
// each (triangle, cell) pair's light leaves in, resolved into a level-0
// texture of D per cell (TEXUNIT_VALUE_DIRECTION; shared/value_grid.glsl:
// directionalFacing), through which cones.glsl's level-0 samples
// (VCT_DIRECTIONAL) and, `directionalChain`, the anisotropic chain's first
// level see a cell's radiance from the side they come from: a wall voxel lit
// on its outer face no longer glows into the room or box behind it
// (docs/BENCHMARKS.md, "Leaks: vct").
#pragma once
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "core/gl_handles.h"
#include "core/scene.h"
#include "illum/resources/light_maps.h"
#include "illum/resources/or_mip_pyramid.h"
#include "illum/resources/value_grids.h"
#include "voxelize/value_textures.h"

namespace vgi {

class ShaderLibrary;
class SparseVoxelOctree;

// What the cone tracers read (shaders/illum/vct/cones.glsl's coneSample and
// emptySkip): the dense ConeVolume, or the sparse octree's (CONE_SVO;
// illum/resources/sparse_octree.h). A method reads it as get<ConeSource>().
class ConeSource {
 public:
  virtual ~ConeSource() = default;
  // Binds the volume and sets cones.glsl's uniforms on `program` (in use), marching `step` cone diameters.
  virtual void bind(ShaderLibrary& shaders, unsigned program, float step) const = 0;
  virtual float voxelSize() const = 0;
};

// Where a volume's radiance comes from (the `radiance` parameter, read once into this): injected from
// the light maps by conservative rasterization (inject) or texel by texel (texels), the atlas
// voxelizer's radiance channel (atlas), or none (the volume holds opacity only).
enum class ConeRadiance { Inject, Texels, Atlas, None };
const char* coneRadianceName(ConeRadiance r);          // its parameter value: "inject", …
ConeRadiance coneRadianceOf(const std::string& name);  // a value the parameter allowed
// Whether a volume's radiance is injected from the light maps (inject, texels).
inline bool injectsRadiance(ConeRadiance r) { return r == ConeRadiance::Inject || r == ConeRadiance::Texels; }

// The fixed-point sums vct's radiance injection writes per slot — a cell of
// the dense volume (x fastest) or a leaf of the sparse octree — as
// shared/value_grid.glsl defines them: a count (4 bytes) and rgb sums (16),
// with the word of the first pass' maximum, the sums' fixed-point range;
// `directional`: also the direction sums (16 bytes).
// The largest of `cells` words of buffer cellMax (non-negative float bits: the injection's per-cell
// maxima, shaders/illum/vct/cell_max_reduce.comp) into word 0 of buffer result, by atomicMax: the
// caller clears it first (or keeps a bound it already holds).
void reduceCellMax(ShaderLibrary& shaders, unsigned cellMax, uint64_t cells, unsigned result);

class InjectionSums {
 public:
  // Buffers for `slots` slots, zero (checked against the GL memory budget). cellMax (a scene with
  // dynamic meshes, dense slots): also per slot its pairs' largest radiance, for region fills.
  void allocate(uint64_t slots, bool directional = false, bool cellMax = false);
  // Clears the sums and injects into them (radiance inject or texels; `octree`:
  // the slots are its leaves, cells outside it left out); returns the range.
  //   inject  the light maps' shadow-tested diffuse light of every (triangle,
  //           cell) pair of the three-axis conservative rasterization of `box`
  //           (shaders/illum/vct/inject.frag);
  //   texels  the 2013 article's: each reflective-shadow-map texel into the
  //           cell its surface point falls in (inject_texels.comp; `maps` reflective).
  // reuseRange > 0 (a frame of an animation: the last fill's range): no pass for the maximum — the
  // sums' pass with that range takes it too, and only where it differs are the sums injected again
  // with it. Either way the range is this fill's own maximum: the sums a fresh fill makes, bit for bit.
  // smallCells: inject's triangles whose bounding box spans at most this many cells are lit
  // triangle-parallel in the geometry shader (conservative.geom.glsl, INJECT_HYBRID: the pairs the
  // rasterization would visit), the rest through it; 0: all through it.
  // region (with reuseRange, inject, dense slots allocated with cellMax): only the pairs of these
  // cells are injected again — the cells a moving mesh and its shadow changed; every other cell's
  // pairs are the last fill's — and the range is the largest of the per-cell maxima; where that is
  // not the last fill's range, all of them are injected again with it (still the fresh fill's sums).
  float inject(SceneResources& res, const GridBox& box, ConeRadiance radiance, const LightMapNeed& maps,
               float bias, float normalOffset, int smallCells, const SparseVoxelOctree* octree,
               Profiler& profiler, float reuseRange = 0.0f, const CellRange* region = nullptr);
  unsigned counts() const { return counts_.get(); }
  unsigned sums() const { return sums_.get(); }
  unsigned directions() const { return directions_.get(); }  // 0 unless directional
  float radianceMax() const { return radianceMax_; }
  // The slots the last fill injected (all, or a region's).
  uint64_t injectedSlots() const { return injected_; }
  double bytes() const { return double(slots_) * ((directions_ ? 36.0 : 20.0) + (cellMax_ ? 4.0 : 0.0)); }

 private:
  GlBuffer counts_, sums_, max_, directions_, cellMax_;
  uint64_t slots_ = 0, injected_ = 0;
  float radianceMax_ = 1.0f;
};

struct ConeVolumeNeed {
  static constexpr const char* kKind = "cone_volume";
  static const ResourceKind& row();  // its row of the kinds table (coneVolumeKind())
  BinaryGridNeed grid;               // cubic cells; with radiance=atlas its values hold "radiance"
  ConeRadiance radiance = ConeRadiance::Inject;
  bool anisotropic = true;
  bool directional = false;       // inject: the level-0 direction of the leaving light, for level-0 samples
  bool directionalChain = false;  // … and the anisotropic chain's first level
  std::optional<LightMapNeed> lightMaps;   // inject, atlas: the direct light's maps
  float bias = 1.0f, normalOffset = 0.0f;  // inject: the maps' shadow test (texels, voxels)
  int injectSmall =
      27;  // inject: triangles whose box spans at most this many cells are lit triangle-parallel
  nlohmann::json key() const;       // grid, radiance, anisotropic, directional: what is allocated
                                    // and built
  nlohmann::json settings() const;  // the light maps and their shadow test: what injection reads
  OrMipPyramidNeed pyramid() const { return {grid}; }
  ValueGridNeed valueGrids() const;  // radiance=atlas: the volume
};

class ConeVolume : public Resource, public ConeSource {
 public:
  explicit ConeVolume(const ConeVolumeNeed& need) : need_(need) {}
  bool update(SceneResources& res, const ResourceNeed& need, Profiler& profiler) override;
  bool relight(SceneResources& res, const ResourceNeed& need, Profiler& profiler) override;
  nlohmann::json stats() override;
  void* offer(const std::type_info& t) override { return offerOf(t, this, static_cast<ConeSource*>(this)); }

  void bind(ShaderLibrary& shaders, unsigned program, float step) const override;
  const ValueTextures& textures() const { return *volume_; }
  float voxelSize() const override { return voxel_; }

 private:
  void allocate(SceneResources& res);                  // the volume of its own and its sums
  void fill(SceneResources& res, Profiler& profiler);  // (re)fills it: injection, resolve
  ConeVolumeNeed need_;
  std::string filledFor_;            // the settings of the last fill (an adopted volume may get others)
  std::vector<Light> filledLights_;  // … its lights
  float filledAt_ = 0;               // … its scene time
  // The cells a fill at the scene's time now can change against one at `before` with the same lights:
  // the dynamic meshes' bounds then and now and what they shadow; none: all of them.
  std::optional<CellRange> changedCells(SceneResources& res, float before) const;
  const ValueTextures* volume_ = nullptr;  // own_, or the value grids' (radiance=atlas)
  std::unique_ptr<ValueTextures> own_;
  InjectionSums sums_;   // also with radiance=none: the resolve reads zero counts
  GlTexture direction_;  // directional: D per cell (RGBA8_SNORM, level 0)
  float voxel_ = 0.0f;
};

// Binds `volume` for cones.glsl on `program` (in use): textures and uniforms.
void bindConeVolume(const ValueTextures& volume, ShaderLibrary& shaders, unsigned program, float step);

ResourceKind coneVolumeKind();

}  // namespace vgi
