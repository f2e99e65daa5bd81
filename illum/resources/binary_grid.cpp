#include "illum/resources/binary_grid.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <optional>

#include "core/build_info.h"
#include "core/gl_context.h"
#include "core/hash.h"
#include "core/params.h"
#include "core/profiler.h"
#include "core/scene.h"
#include "core/shader_library.h"
#include "voxelize/atlas.h"
#include "voxelize/atlas_voxelizer.h"
#include "voxelize/setup_cache.h"
#include "voxelize/value_sums_cache.h"
#include "voxelize/voxelizer.h"

namespace vgi {

BinaryGridNeed readBinaryGridParams(ParamSet& p, int grids, bool atlasOnly,
                                    const std::string& defaultVoxelizer) {
  BinaryGridNeed g;
  g.resolution = parseResolution(
      p.getString("voxels", "128", "grid resolution N or WxHxD (D a multiple of 128)"), "parameter 'voxels'");
  std::vector<std::string> voxelizers;
  if (atlasOnly)
    voxelizers.push_back("atlas");
  else
    for (auto& v : voxelizerRegistry()) voxelizers.push_back(v.name);
  g.voxelizer =
      p.getString("voxelizer", atlasOnly ? "atlas" : defaultVoxelizer,
                  atlasOnly ? "binary voxelizer: atlas (the multi-valued grids come from its points)"
                            : "binary voxelizer (see vgi voxelize --help)",
                  voxelizers);
  checkGridMemory(g.resolution, grids);
  return g;
}

namespace {

class BinaryGridResource : public Resource {
 public:
  explicit BinaryGridResource(const BinaryGridNeed& n) : need_(n) {}

  bool update(SceneResources& res, const ResourceNeed&, Profiler& prof) override {
    if (builtFor_ && (!res.dynamic() || *builtFor_ == res.time())) return false;  // current
    if (!builtFor_) box_ = fitBox(res);
    const std::optional<uint64_t> cacheKey = gridCacheKey(res);
    if (cacheKey && readCachedGrid(*cacheKey, prof)) {
      builtFor_ = res.time();
      return true;
    }
    VoxelizeRequest vreq;
    vreq.scene = &res.scene();
    vreq.box = box_;
    vreq.time = res.time();
    vreq.threads = res.threads();
    vreq.gl = res.gl();
    vreq.shaders = res.gl() ? &res.shaders() : nullptr;
    vreq.atlasCacheDir = need_.atlasCache ? defaultSetupCacheDir() : "";
    vreq.valueGrids = need_.values;
    vreq.texelsPerVoxel = need_.texelsPerVoxel;
    vreq.atlasResolution = need_.atlasResolution;
    vreq.atlasFootprint = need_.atlasFootprint;
    vreq.hybridCutoff = need_.hybridCutoff;
    counted_ = false;
    const VoxelizerInfo& voxelizer = findVoxelizer(need_.voxelizer);
    if (res.gl() && need_.voxelizer == "atlas") {
      // The atlas voxelizer keeps the static meshes' grid on the GPU and re-inserts the dynamic ones.
      if (!atlas_) atlas_ = std::make_unique<AtlasVoxelizer>(vreq, prof);
      atlas_->voxelizeFrame(res.time(), prof);
    } else if (res.dynamic() && voxelizer.perTriangle) {
      // The static meshes' grid is voxelized once and kept; each frame voxelizes the dynamic meshes
      // alone and ORs it in: the same grid as the whole scene's (each triangle sets its cells alone).
      if (!static_) {
        const Scene still = res.scene().meshGeometry(false);
        vreq.scene = &still;
        static_ = std::make_unique<BinaryGrid>(voxelizer.run(vreq, prof, staticStats_));
      }
      const Scene moving = res.scene().meshGeometry(true);
      vreq.scene = &moving;
      grid_ = std::make_unique<BinaryGrid>(voxelizer.run(vreq, prof, voxelizerStats_));
      std::vector<uint32_t>& w = grid_->words();
      const std::vector<uint32_t>& k = static_->words();
      for (size_t i = 0; i < w.size(); ++i) w[i] |= k[i];
      voxelizerStats_["static_meshes"] = staticStats_;
      voxelizerStats_["static_meshes"]["kept"] = true;
    } else {
      grid_ = std::make_unique<BinaryGrid>(voxelizer.run(vreq, prof, voxelizerStats_));
    }
    builtFor_ = res.time();
    if (cacheKey) writeCachedGrid(*cacheKey, prof);
    return true;
  }

  nlohmann::json stats() override {
    if (!counted_) {  // once per build: the atlas grid is read back
      if (atlas_) voxelizerStats_ = atlas_->stats();
      voxelsSet_ = atlas_ ? atlas_->readFrame().count() : grid_->count();
      counted_ = true;
    }
    const glm::uvec3 r = need_.resolution;
    // Where it lives: the atlas voxelizer's grids, sums and targets on the GPU, another voxelizer's
    // (or the set-up cache's) grid on the host (the pyramid holds its GPU copy), cached sums on the GPU.
    const double bytes =
        atlas_ ? atlas_->gpuBytes() : double(grid_->words().size()) * 4.0 + (sums_ ? sums_->gpuBytes() : 0.0);
    return {{"resolution", {r.x, r.y, r.z}},
            {"voxelizer", need_.voxelizer},
            {"voxels_set", voxelsSet_},
            {"bytes", bytes},
            {"memory", atlas_ ? "gpu" : (sums_ ? "host (grid), gpu (value sums)" : "host")},
            {"stats", voxelizerStats_},
            {"cache", cacheState_}};
  }

  void* offer(const std::type_info& t) override {
    return offerOf(t, builtFor_ ? &box_ : nullptr, atlas_.get(), grid_.get(), sums_.get());
  }

 private:
  // One grid box for the whole animation: the union of the frames' bounds.
  GridBox fitBox(const SceneResources& res) const {
    Bounds b;
    for (float t : res.frameTimes().empty() ? std::vector<float>{res.time()} : res.frameTimes()) {
      Bounds f = res.scene().bounds(t);
      b.extend(f.lo);
      b.extend(f.hi);
      if (!res.dynamic()) break;
    }
    GridBox box = fitGridBox(b, need_.resolution);
    return need_.cubicCells ? cubicCellBox(box) : box;
  }

  // The set-up cache's key of this grid: a digest of everything the voxelization reads — the scene's
  // triangles at this time (world space, with the mesh each belongs to), the box, the voxelizer and its
  // settings, the GL renderer (rasterization may differ between devices), the voxelization shaders and
  // this program's build (the executable's size and time, so a rebuilt vgi never reads an older one's
  // grid). None for a dynamic scene, a grid with the radiance channel, or with the cache off.
  std::optional<uint64_t> gridCacheKey(const SceneResources& res) const {
    // (The radiance channel follows the lights: a grid that carries it is built each time; the other
    // value channels' sums are kept beside the grid, value_sums_cache.h.)
    const auto& v = need_.values;
    if (!need_.gridCache || res.dynamic() || std::find(v.begin(), v.end(), "radiance") != v.end())
      return std::nullopt;
    if (defaultSetupCacheDir().empty()) return std::nullopt;
    const FlatScene flat = flatten(res.scene(), res.time());
    uint64_t h = fnv1a(std::string("binary_grid v1 ") + gitRevision());
    h = fnv1a(flat.positions.data(), flat.positions.size() * sizeof(glm::vec3), h);
    h = fnv1a(flat.meshOfTriangle.data(), flat.meshOfTriangle.size() * sizeof(int), h);
    const shared::GridParams g = box_.params();
    h = fnv1a(&g, sizeof g, h);
    h = fnv1a(need_.key().dump(), h);
    h = fnv1a(res.gl() ? res.gl()->renderer() : std::string("cpu"), h);
    std::error_code ec;
    const auto exe = std::filesystem::path("/proc/self/exe");
    const uint64_t exeSize = std::filesystem::file_size(exe, ec);
    const auto exeTime = std::filesystem::last_write_time(exe, ec).time_since_epoch().count();
    h = fnv1a(&exeSize, sizeof exeSize, h);
    h = fnv1a(&exeTime, sizeof exeTime, h);
    const uint64_t shaders = filesDigest({defaultShaderDir() + "/voxelize", defaultShaderDir() + "/shared"});
    return fnv1a(&shaders, sizeof shaders, h);
  }

  // The words of the cached grid, when the entry is whole; the grid then lives on the host (the pyramid
  // uploads it) and the voxelizer never runs.
  bool readCachedGrid(uint64_t key, Profiler& prof) {
    auto s = prof.scope("grid_cache_read");
    std::vector<uint8_t> payload;
    BinaryGrid grid(box_);
    std::unique_ptr<CachedValueSums> sums;
    const glm::uvec3 r = box_.resolution;
    if (!need_.values.empty()) {  // the value channels' sums first: without them the grid is no use
      std::vector<uint8_t> packed;
      if (readSetupCache(defaultSetupCacheDir(), "values", key, packed))
        sums = CachedValueSums::unpack(packed.data(), packed.size(), size_t(r.x) * r.y * r.z,
                                       valueChannelMask(need_.values));
    }
    if ((!need_.values.empty() && !sums) || !readSetupCache(defaultSetupCacheDir(), "grid", key, payload) ||
        payload.size() != grid.words().size() * sizeof(uint32_t)) {
      cacheState_ = "miss";
      return false;
    }
    std::memcpy(grid.words().data(), payload.data(), payload.size());
    grid_ = std::make_unique<BinaryGrid>(std::move(grid));
    sums_ = std::move(sums);
    atlas_.reset();
    voxelizerStats_ = nlohmann::json::object();
    counted_ = false;
    cacheState_ = "hit";
    return true;
  }

  void writeCachedGrid(uint64_t key, Profiler& prof) {
    auto s = prof.scope("grid_cache_write");
    bool written = true;
    if (!need_.values.empty()) {
      const glm::uvec3 r = box_.resolution;
      const std::vector<uint8_t> packed = packValueSums(atlas_->valueBuffers(), size_t(r.x) * r.y * r.z);
      written = writeSetupCache(defaultSetupCacheDir(), "values", key, packed.data(), packed.size());
    }
    const BinaryGrid grid = atlas_ ? atlas_->readFrame() : *grid_;
    written = written && writeSetupCache(defaultSetupCacheDir(), "grid", key, grid.words().data(),
                                         grid.words().size() * sizeof(uint32_t));
    cacheState_ = written ? "written" : "unwritable";
  }

  BinaryGridNeed need_;
  GridBox box_;
  std::string cacheState_ = "off";  // off, hit, miss (then written or unwritable)
  std::optional<float> builtFor_;   // the animation time it was built for
  std::unique_ptr<AtlasVoxelizer> atlas_;
  std::unique_ptr<BinaryGrid> grid_;
  std::unique_ptr<BinaryGrid> static_;     // an animation's static meshes (a per-triangle voxelizer's)
  std::unique_ptr<CachedValueSums> sums_;  // the value channels' sums, read from the set-up cache
  nlohmann::json voxelizerStats_ = nlohmann::json::object(), staticStats_ = nlohmann::json::object();
  uint64_t voxelsSet_ = 0;
  bool counted_ = false;
};

}  // namespace

ResourceKind binaryGridKind() {
  return {"binary_grid",
          "the scene voxelized into bitmask columns over a tight box (any voxelizer; an animation keeps the "
          "static meshes' grid)",
          [](const ResourceNeed&) { return std::vector<ResourceNeed>{}; },
          [](const ResourceNeed& n, const SceneNeeds&, const std::string& method, bool gl) {
            const BinaryGridNeed& g = n.spec<BinaryGridNeed>();
            const VoxelizerInfo& v = findVoxelizer(g.voxelizer);
            if (v.needsGl && !gl)
              fail("method '", method, "' runs on the CPU but voxelizer '", v.name, "' needs GL");
            if (!g.values.empty() && !gl)
              fail("method '", method, "' runs on the CPU but asks for multi-valued grids (GL textures)");
            if (!g.values.empty() && g.voxelizer != "atlas")
              fail("method '", method,
                   "' asks for multi-valued grids without the atlas voxelizer's binary grid (",
                   "voxelizer=", g.voxelizer, "): their values come from its atlas points");
          },
          [](const ResourceNeed&) { return std::vector<std::string>{"binary_grid"}; },
          [](const ResourceNeed& n, SceneResources&) -> std::unique_ptr<Resource> {
            return std::make_unique<BinaryGridResource>(n.spec<BinaryGridNeed>());
          },
          "grid"};
}

const ResourceKind& BinaryGridNeed::row() {
  static const ResourceKind k = binaryGridKind();
  return k;
}

}  // namespace vgi
