#include "illum/resources/value_grids.h"

#include <unistd.h>

#include "core/gpu_scene.h"
#include "core/profiler.h"
#include "core/scene.h"
#include "illum/framework/sample_loop.h"
#include "shaders/shared/value_grid.glsl"
#include "voxelize/atlas_voxelizer.h"
#include "voxelize/value_grids.h"
#include "voxelize/value_sums_cache.h"

namespace vgi {

namespace {

class ValueGridsResource : public Resource {
 public:
  explicit ValueGridsResource(const ValueGridNeed& n) : need_(n) {}

  bool update(SceneResources& res, const ResourceNeed& need, Profiler& prof) override {
    need_ = need.spec<ValueGridNeed>();  // adopted: the light maps may be others
    // The sums come from the atlas voxelizer, or (a static scene's grid read from the set-up cache,
    // never with radiance) from the cache.
    AtlasVoxelizer* atlas = res.tryGet<AtlasVoxelizer>(need_.grid);
    // With area lights the radiance follows the sample's lights: beginSample relights it.
    const bool radiance = atlas && atlas->hasRadiance() && !res.sampleLights();
    const bool relit = radiance && need_.lightMaps && res.changed(*need_.lightMaps);
    if (tex_ && !res.changed(need_.grid) && !relit) return false;
    // A frame of an animation changes the sums only in the cells the dynamic meshes left and entered
    // (the static sums are restored as they were): only those are resolved again — unless radiance is
    // inserted, which the moved shadows change everywhere.
    std::optional<CellRange> cells;
    if (tex_ && atlas && !radiance) cells = movedCells(res, resolvedAt_);
    if (!tex_)
      tex_ = std::make_unique<ValueTextures>(res.get<GridBox>(need_.grid), need_.grid.values, need_.mips);
    if (radiance) insertRadiance(res, *atlas, prof);
    tex_->resolve(atlas ? atlas->valueBuffers() : res.get<CachedValueSums>(need_.grid).buffers(),
                  res.shaders(), prof, 0, 0, cells);
    resolvedAt_ = res.time();
    return true;
  }

  bool relight(SceneResources& res, const ResourceNeed&, Profiler& prof) override {
    AtlasVoxelizer* atlas = res.tryGet<AtlasVoxelizer>(need_.grid);
    if (!atlas || !atlas->hasRadiance()) return false;
    insertRadiance(res, *atlas, prof);
    tex_->resolve(atlas->valueBuffers(), res.shaders(), prof);
    resolvedAt_ = res.time();
    return true;
  }

  nlohmann::json stats() override { return tex_->describe(); }
  void* offer(const std::type_info& t) override { return offerOf(t, tex_.get()); }

 private:
  void insertRadiance(SceneResources& res, AtlasVoxelizer& atlas, Profiler& prof) {
    const GpuScene& gpu = res.get<GpuScene>();
    const LightMaps& maps = res.get<LightMaps>(*need_.lightMaps);
    atlas.insertRadiance(
        res.time(),
        [&](unsigned program) {
          gpu.bind(res.shaders(), program);
          maps.bind();
        },
        prof);
  }

  // The cells the dynamic meshes' bounds at `before` and now cover, a cell of margin around them.
  CellRange movedCells(SceneResources& res, float before) const {
    Bounds b = res.scene().dynamicBounds(before);
    const Bounds now = res.scene().dynamicBounds(res.time());
    if (!now.empty()) b.extend(now.lo), b.extend(now.hi);
    return boundsCells(tex_->box(), b, 1, 2);
  }

  ValueGridNeed need_;
  std::unique_ptr<ValueTextures> tex_;
  float resolvedAt_ = 0;  // the scene time of the sums the textures were last resolved from
};

void check(const ResourceNeed& need, const SceneNeeds&, const std::string& method, bool gl) {
  const ValueGridNeed& v = need.spec<ValueGridNeed>();
  // (The grid's own check refuses values on the CPU and from other voxelizers than atlas.)
  requireGl(need, method, gl);
  if (v.grid.values.empty()) fail("method '", method, "' asks for multi-valued grids with no channel");
  for (auto& c : v.grid.values)
    if (valueChannelIndex(c) == shared::VALUE_CHANNEL_RADIANCE && !v.lightMaps)
      fail("method '", method,
           "' asks for the radiance channel without light maps (its direct light comes from them)");
  // Memory: per cell the atomic sums (uvec4 per channel) and the count, and
  // the textures (occupancy, count, each channel's format), the chains ×8/7.
  const glm::uvec3 r = v.grid.resolution;
  const double cells = double(r.x) * r.y * r.z;
  const double chain = v.mips == ValueMips::None ? 1.0 : 8.0 / 7.0;
  double perCell = 4.0 + (4.0 + 1.0) * chain;
  for (auto& c : v.grid.values) {
    const bool rgba8 = valueChannelIndex(c) == shared::VALUE_CHANNEL_ALBEDO;
    perCell += 16.0 + (rgba8 ? 4.0 : 8.0) * chain;
    if (v.mips == ValueMips::Anisotropic) perCell += 6.0 * 8.0 / 8.0 * chain;
  }
  const double phys = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  if (cells * perCell > 0.5 * phys)
    fail("method '", method, "': multi-valued grids at ", r.x, "x", r.y, "x", r.z, " need ",
         cells * perCell / double(1 << 20), " MiB; this machine has ", phys / double(1 << 20),
         " MiB of memory (at most half of it is used for grids): use a smaller 'voxels'");
}

}  // namespace

void valueTexturesInput(Frame& f, unsigned) { f.resources.get<ValueTextures>().bind(); }

ResourceKind valueGridsKind() {
  return {"value_grids",
          "normals, albedo, glossiness, direct radiance per cell of the atlas grid as 3D textures (+ mips)",
          [](const ResourceNeed& n) {
            const ValueGridNeed& v = n.spec<ValueGridNeed>();
            std::vector<ResourceNeed> d{v.grid};
            if (v.lightMaps) d.push_back(*v.lightMaps);
            return d;
          },
          check,
          [](const ResourceNeed& n) {
            std::vector<std::string> names{"value_grids"};
            if (n.spec<ValueGridNeed>().mips != ValueMips::None) names.push_back("value_mips");
            return names;
          },
          [](const ResourceNeed& n, SceneResources&) -> std::unique_ptr<Resource> {
            return std::make_unique<ValueGridsResource>(n.spec<ValueGridNeed>());
          },
          "value_grids"};
}

const ResourceKind& ValueGridNeed::row() {
  static const ResourceKind k = valueGridsKind();
  return k;
}

}  // namespace vgi
