#include "voxelize/voxelizer.h"

#include "core/error.h"
#include "voxelize/atlas_voxelizer.h"
#include "voxelize/conservative_voxelizer.h"
#include "voxelize/exact_voxelizer.h"
#include "voxelize/slicemap_voxelizer.h"

namespace vgi {

const std::vector<VoxelizerInfo>& voxelizerRegistry() {
  static const std::vector<VoxelizerInfo> table = {
      {"atlas", "GL atlas voxelization (VGI section 3): atlas rendering + one point per texel", true, false,
       [](const VoxelizeRequest& r, Profiler& p, nlohmann::json& s) { return voxelizeAtlasGl(r, p, s); }},
      {"slicemap", "GL single-pass slicemap (Eisemann & Decoret 2006): one raster pass along depth", true,
       true,
       [](const VoxelizeRequest& r, Profiler& p, nlohmann::json& s) { return voxelizeSlicemapGl(r, p, s); }},
      {"conservative", "GL three-axis conservative rasterization (dominant axis, expanded triangles)", true,
       true,
       [](const VoxelizeRequest& r, Profiler& p, nlohmann::json& s) {
         return voxelizeConservativeGl(r, p, s);
       }},
      {"hybrid",
       "GL hybrid (Rauwendaal & Bailey 2013): small triangles triangle-parallel in the geometry shader, "
       "large "
       "ones conservatively rasterized, one pass",
       true, true,
       [](const VoxelizeRequest& r, Profiler& p, nlohmann::json& s) { return voxelizeHybridGl(r, p, s); }},
      {"exact", "CPU triangle-box overlap (separating axes): the reference", false, true,
       [](const VoxelizeRequest& r, Profiler& p, nlohmann::json&) {
         auto s = p.scope("voxelize_exact");
         return voxelizeExact(*r.scene, r.box, r.time, r.threads);
       }},
  };
  return table;
}

const VoxelizerInfo& findVoxelizer(const std::string& name) {
  std::string known;
  for (auto& v : voxelizerRegistry()) {
    if (v.name == name) return v;
    known += (known.empty() ? "" : ", ") + v.name;
  }
  fail("--voxelizer: unknown voxelizer '", name, "' (known: ", known, ")");
}

}  // namespace vgi
