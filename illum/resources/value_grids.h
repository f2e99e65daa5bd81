// Resource kind "value_grids": multi-valued grids as 3D textures
// (voxelize/value_textures.h: normal, albedo, glossy, radiance; VGI §3) over
// the atlas binary grid's box, resolved from the sums its insertion
// accumulated (BinaryGridNeed::values), with an optional isotropic or
// anisotropic mip chain ("value_mips"). The radiance channel is the direct
// light of the light maps at each atlas point: inserted again whenever they
// are drawn again. Offers the ValueTextures.
#pragma once
#include <optional>

#include "illum/resources/binary_grid.h"
#include "illum/resources/light_maps.h"
#include "voxelize/value_textures.h"

namespace vgi {

struct ValueGridNeed {
  static constexpr const char* kKind = "value_grids";
  static const ResourceKind& row();  // its row of the kinds table (valueGridsKind())
  BinaryGridNeed grid;               // voxelizer atlas; grid.values are the channels
  ValueMips mips = ValueMips::None;
  std::optional<LightMapNeed> lightMaps;  // the radiance channel's direct light
  nlohmann::json key() const { return {{"grid", grid.key()}, {"mips", int(mips)}}; }
  nlohmann::json settings() const { return lightMaps ? lightMaps->key() : nlohmann::json(nullptr); }
};

ResourceKind valueGridsKind();

class Frame;
// A compute pass's input (illum/framework/compute_pass.h): the value grids' 3D textures.
void valueTexturesInput(Frame& f, unsigned program);

}  // namespace vgi
