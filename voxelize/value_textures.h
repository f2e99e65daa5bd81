// Multi-valued grids on the GPU for GLSL consumers: the atlas voxelizer's
// fixed-point sums resolved into one 3D texture per channel, with optional mip
// chains (isotropic, or six-direction anisotropic: the hook voxel cone tracing
// needs), sampled through shaders/shared/value_grid.glsl (valueUvw,
// anisoFaces/anisoWeights; the mip kernels boxMean8/anisoReduce are what the
// C++ builder below runs too).
//
// Textures (texture units in shaders/shared/bindings.glsl), texel = one cell,
// x fastest; an empty cell is 0 in every texture, so with linear filtering
// channel / occupancy is the point-weighted mean of the cells it blends:
// | texture   | format   | content                                                    |
// |-----------|----------|------------------------------------------------------------|
// | count     | R32UI    | atlas points of the cell (integers: GPU == CPU bit for bit) |
// | occupancy | R8       | 1 where the cell has points                                |
// | normal    | RGBA16F  | mean normal xyz (not renormalised: length < 1 = spread), w 0 |
// | albedo    | RGBA8    | mean albedo rgb (linear; 1/255 steps), a 0                 |
// | glossy    | RGBA16F  | mean ks rgb, w the mean exponent code log2(1 + e)          |
// | radiance  | RGBA16F  | mean diffuse direct radiance rgb (VGI §3, Table 2), premultiplied: w = occupancy |
// Half floats keep 11 significant bits (normals to 5·10⁻⁴); albedo is 8-bit
// as in the atlas' source textures. The count texture has no mips.
//
// Mips: `isotropic` gives every texture (count excepted) a full chain of
// 2×2×2 means; `anisotropic` adds six direction textures for normal, albedo
// and radiance from the grid's level 1 on (level L of the grid is level L−1
// of a face texture), RGBA16F with the occupancy composed front to back as
// alpha. Glossy has no anisotropic chain (its four components leave no room
// for the alpha).
#pragma once
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/gl_handles.h"
#include "voxelize/voxel_grid.h"

namespace vgi {

class Profiler;
class ShaderLibrary;

enum class ValueMips { None, Isotropic, Anisotropic };

const char* valueMipsName(ValueMips m);

// The GL buffers of a multi-valued insertion (AtlasVoxelizer::valueBuffers()).
struct ValueSumBuffers {
  unsigned counts = 0;
  unsigned sums[4] = {0, 0, 0, 0};  // normal, albedo, glossy, radiance (0 = not built)
  float radianceMax = 0;            // the radiance sums' fixed-point range
};

class ValueTextures {
 public:
  ValueTextures(const GridBox& box, std::vector<std::string> channels, ValueMips mips);
  ~ValueTextures();
  ValueTextures(const ValueTextures&) = delete;
  ValueTextures& operator=(const ValueTextures&) = delete;

  // Level 0 from the sums ("value_resolve"), then the mips ("value_mips").
  // occupancyWords: a binary grid's words (an OR-mip pyramid, level 0 first)
  // that decide the occupancy instead of count > 0 (cone tracing's opacity
  // from any voxelizer); 0: the counts decide. radianceDirection: a level-0
  // texture of the direction each cell's radiance leaves in (vct's
  // `directional`: illum/resources/cone_volume.h), which the radiance's
  // anisotropic chain then reads its first level through (value_mip.comp, DIRECTIONAL).
  // cells: level 0 is resolved within [lo, hi) only (the sums changed nowhere else) and each mip
  // level over their parents; none: everywhere.
  void resolve(const ValueSumBuffers& sums, ShaderLibrary& shaders, Profiler& profiler,
               unsigned occupancyWords = 0, unsigned radianceDirection = 0,
               const std::optional<CellRange>& cells = std::nullopt);
  // Binds count, occupancy and the channels at their TEXUNIT_VALUE_* units.
  void bind() const;
  // Binds the six faces of `channel`'s anisotropic chain at TEXUNIT_VALUE_ANISO + face.
  void bindAniso(const std::string& channel) const;

  const GridBox& box() const { return box_; }
  const std::vector<std::string>& channels() const { return channels_; }
  ValueMips mips() const { return mips_; }
  int levels() const { return levels_; }  // of the isotropic chain (1 without mips)
  bool has(const std::string& channel) const;

  // Read-backs (tests, `vgi voxelize`): a level of a channel, "occupancy", or
  // face `face` of an anisotropic chain (its level L−1 = the grid's level L).
  std::vector<glm::vec4> read(const std::string& channel, int level = 0) const;
  std::vector<glm::vec4> readAniso(const std::string& channel, int face, int gridLevel) const;
  std::vector<uint32_t> readCounts() const;
  glm::uvec3 levelSize(int level) const;
  nlohmann::json describe() const;  // formats, levels, bytes, the last resolve's cells

 private:
  unsigned textureOf(const std::string& channel) const;
  GridBox box_;
  std::vector<std::string> channels_;
  ValueMips mips_;
  int levels_ = 1;
  GlTexture count_, occupancy_, channel_[4];
  GlTexture aniso_[4][6];  // normal, albedo, radiance (glossy unused)
  size_t bytes_ = 0;
  uint64_t resolvedCells_ = 0;  // by the last resolve
};

// A 3D texture of a grid's cells: `levels` levels of `format`, filtered
// (linear, and between levels) or not, 0 outside the grid (a border of 0).
GlTexture makeGridTexture3D(glm::uvec3 size, int levels, unsigned format, bool linear);

// The C++ builders of one mip level through the same kernels (tests compare
// the GPU's levels with these): `in` is a level of size inSize, x fastest.
std::vector<glm::vec4> isoMipLevel(const std::vector<glm::vec4>& in, glm::uvec3 inSize);
std::vector<glm::vec4> anisoMipLevel(const std::vector<glm::vec4>& in, glm::uvec3 inSize, uint32_t face);

}  // namespace vgi
