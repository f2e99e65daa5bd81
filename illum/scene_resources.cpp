#include "illum/scene_resources.h"

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "core/emitters.h"
#include "core/error.h"
#include "core/gpu_scene.h"
#include "core/params.h"
#include "core/profiler.h"
#include "core/scene.h"
#include "illum/light_maps.h"
#include "illum/occluders.h"
#include "shaders/shared/value_grid.glsl"
#include "traverse/embree_tracer.h"
#include "traverse/gl_ray_tracer.h"
#include "traverse/or_mip_pyramid.h"
#include "voxelize/atlas.h"
#include "voxelize/atlas_voxelizer.h"
#include "voxelize/value_grids.h"
#include "voxelize/voxelizer.h"

namespace vgi {

std::vector<std::string> SceneNeeds::names() const {
  std::vector<std::string> n;
  if (gbuffer) n.push_back("gbuffer");
  if (lightMaps) n.push_back(lightMaps->reflective ? "rsm" : "light_maps");
  if (binaryGrid) n.push_back("binary_grid");
  if (valueGrids) {
    n.push_back("value_grids");
    if (valueGrids->mips != ValueMips::None) n.push_back("value_mips");
  }
  if (orMipPyramid) n.push_back("or_mip_pyramid");
  if (bvh) n.push_back("bvh");
  if (occluders) n.push_back("occluders");
  return n;
}

void SceneNeeds::check(const std::string& method, bool gl) const {
  if (orMipPyramid && !binaryGrid)
    fail("method '", method, "' asks for an OR-mip pyramid without a binary grid");
  if (gl && binaryGrid && !orMipPyramid)
    fail("method '", method,
         "' asks for a GL binary grid without its pyramid (GLSL reads the grid as its level 0)");
  if (!gl && (gbuffer || lightMaps || occluders))
    fail("method '", method, "' runs on the CPU but asks for GL resources (G-buffer, light maps, occluders)");
  if (valueGrids) {
    if (!gl) fail("method '", method, "' runs on the CPU but asks for value-grid 3D textures");
    if (!binaryGrid || binaryGrid->voxelizer != "atlas")
      fail("method '", method, "' asks for multi-valued grids without the atlas voxelizer's binary grid (",
           binaryGrid ? "voxelizer=" + binaryGrid->voxelizer : std::string("no binary grid"),
           "): their values come from its atlas points");
    if (valueGrids->channels.empty())
      fail("method '", method, "' asks for multi-valued grids with no channel");
    for (auto& c : valueGrids->channels)
      if (valueChannelIndex(c) == shared::VALUE_CHANNEL_RADIANCE && !lightMaps)
        fail("method '", method,
             "' asks for the radiance channel without light maps (its direct light comes from them)");
    // Memory: per cell the atomic sums (uvec4 per channel) and the count, and
    // the textures (occupancy, count, each channel's format), the chains ×8/7.
    const glm::uvec3 r = binaryGrid->resolution;
    const double cells = double(r.x) * r.y * r.z;
    const double chain = valueGrids->mips == ValueMips::None ? 1.0 : 8.0 / 7.0;
    double perCell = 4.0 + (4.0 + 1.0) * chain;
    for (auto& c : valueGrids->channels) {
      const bool rgba8 = valueChannelIndex(c) == shared::VALUE_CHANNEL_ALBEDO;
      perCell += 16.0 + (rgba8 ? 4.0 : 8.0) * chain;
      if (valueGrids->mips == ValueMips::Anisotropic) perCell += 6.0 * 8.0 / 8.0 * chain;
    }
    const double phys = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
    if (cells * perCell > 0.5 * phys)
      fail("method '", method, "': multi-valued grids at ", r.x, "x", r.y, "x", r.z, " need ",
           cells * perCell / double(1 << 20), " MiB; this machine has ", phys / double(1 << 20),
           " MiB of memory (at most half of it is used for grids): use a smaller 'voxels'");
  }
  if (binaryGrid) {
    const VoxelizerInfo& v = findVoxelizer(binaryGrid->voxelizer);
    if (v.needsGl && !gl) fail("method '", method, "' runs on the CPU but voxelizer '", v.name, "' needs GL");
  }
}

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

bool sameLightMaps(const std::optional<LightMapNeed>& x, const std::optional<LightMapNeed>& y) {
  return bool(x) == bool(y) && (!x || (x->resolution == y->resolution && x->reflective == y->reflective));
}

// The needs that decide the grid and what is built over it: the binary grid, the value grids, the pyramid.
bool sameGrid(const SceneNeeds& a, const SceneNeeds& b) {
  const auto &x = a.binaryGrid, &y = b.binaryGrid;
  const auto &u = a.valueGrids, &v = b.valueGrids;
  return bool(x) == bool(y) &&
         (!x || (x->resolution == y->resolution && x->voxelizer == y->voxelizer &&
                 x->cubicCells == y->cubicCells)) &&
         bool(u) == bool(v) && (!u || (u->channels == v->channels && u->mips == v->mips)) &&
         a.orMipPyramid == b.orMipPyramid;
}

}  // namespace

bool SceneNeeds::operator==(const SceneNeeds& o) const {
  return gbuffer == o.gbuffer && sameLightMaps(lightMaps, o.lightMaps) && sameGrid(*this, o) &&
         bvh == o.bvh && occluders == o.occluders;
}

SceneResources::SceneResources(const Scene& scene, SceneNeeds needs, GlContext* gl, ShaderLibrary* shaders,
                               std::vector<float> frameTimes, int threads)
    : scene_(scene),
      needs_(std::move(needs)),
      gl_(gl),
      shaders_(shaders),
      frameTimes_(std::move(frameTimes)),
      threads_(threads) {
  VGI_CHECK(bool(gl_) == bool(shaders_));
}

SceneResources::~SceneResources() = default;

bool SceneResources::update(float time, Profiler& prof) {
  const bool dynamic = scene_.hasDynamicMeshes();
  rebuilt_ = first_ || (dynamic && time != time_);
  time_ = time;
  if (!rebuilt_) {
    if (lightsChanged_) relight(prof);
    lightsChanged_ = false;
    return false;
  }
  const bool first = first_;
  first_ = false;
  lightsChanged_ = false;

  // An adopted grid or BVH is current if it was built for this time (or nothing moves).
  const bool keepGrid = gridTime_ && (!dynamic || *gridTime_ == time);
  const bool keepBvh = bvhTime_ && (!dynamic || *bvhTime_ == time);
  gridTime_.reset();
  bvhTime_.reset();
  if (needs_.bvh) {
    if (!keepBvh) {
      auto s = prof.scope("build_bvh");
      bvh_.reset();
      flat_ = std::make_unique<FlatScene>(flatten(scene_, time));
      bvh_ = std::make_unique<EmbreeTracer>(*flat_);
    }
    emitters_ = std::make_unique<Emitters>(scene_, *flat_);
  } else {
    emitters_ = std::make_unique<Emitters>(Emitters::ofScene(scene_, time));
  }
  const bool gpuScene = needs_.gbuffer || needs_.lightMaps;
  sampleLights_ = gpuScene && !emitters_->empty();
  placeLights();
  if (gpuScene) {
    auto s = prof.scope("upload");
    if (!gpu_)
      gpu_ = std::make_unique<GpuScene>(scene_, time);
    else
      gpu_->setTime(scene_, time);
    gpu_->setLights(lights_);
  }
  if (needs_.occluders) {
    auto s = prof.scope("occluders");
    if (!occluders_)
      occluders_ =
          std::make_unique<Occluders>(scene_, needs_.occluders->triangles, needs_.occluders->tolerance, time);
    else
      occluders_->setTime(time);
  }
  if (needs_.lightMaps) {
    if (!lightMaps_)
      lightMaps_ = std::make_unique<LightMaps>(lights_, *gpu_, needs_.lightMaps->resolution,
                                               needs_.lightMaps->reflective);
    else
      lightMaps_->setLights(lights_, *gpu_);
    if (!sampleLights_) lightMaps_->render(*gpu_, *shaders_, prof);
  }
  if (needs_.binaryGrid && keepGrid) {
    // The grid as it was; only its radiance (if any) depends on these light maps.
    if (!sampleLights_) relightRadiance(prof);  // (with area lights, beginSample does)
  } else if (needs_.binaryGrid) {
    if (first && !hasBox_) {
      // One grid box for the whole animation: the union of the frames' bounds.
      Bounds b;
      for (float t : frameTimes_.empty() ? std::vector<float>{time} : frameTimes_) {
        Bounds f = scene_.bounds(t);
        b.extend(f.lo);
        b.extend(f.hi);
        if (!dynamic) break;
      }
      box_ = fitGridBox(b, needs_.binaryGrid->resolution);
      if (needs_.binaryGrid->cubicCells) box_ = cubicCellBox(box_);
      hasBox_ = true;
    }
    buildGrid(prof);
  }
  return true;
}

void SceneResources::adopt(SceneResources& old) {
  VGI_CHECK(first_ && &old.scene_ == &scene_);
  // Nothing to take when it built nothing, or built for another context (a GL method after a CPU
  // one) or another animation (the grid box spans the frames').
  if (old.first_ || old.gl_ != gl_ || old.frameTimes_ != frameTimes_) return;
  auto take = [&](auto& mine, auto& theirs, const char* name) {
    if (!theirs) return false;
    mine = std::move(theirs);
    adopted_.push_back(name);
    return true;
  };
  if (needs_.gbuffer || needs_.lightMaps) take(gpu_, old.gpu_, "gpu_scene");
  if (gpu_ && needs_.lightMaps && sameLightMaps(needs_.lightMaps, old.needs_.lightMaps))
    take(lightMaps_, old.lightMaps_, needs_.lightMaps->reflective ? "rsm" : "light_maps");
  if (needs_.binaryGrid && old.hasBox_ && sameGrid(needs_, old.needs_) &&
      (old.glPyramid_ || old.cpuPyramid_)) {
    box_ = old.box_;
    hasBox_ = true;
    atlas_ = std::move(old.atlas_);
    take(glPyramid_, old.glPyramid_, "binary_grid");
    take(cpuPyramid_, old.cpuPyramid_, "binary_grid");
    take(valueTextures_, old.valueTextures_, "value_grids");
    if (glPyramid_ || cpuPyramid_) adopted_.push_back("or_mip_pyramid");
    voxelsSet_ = old.voxelsSet_;
    voxelsCounted_ = old.voxelsCounted_;
    voxelizerStats_ = std::move(old.voxelizerStats_);
    gridTime_ = old.time_;
  }
  if (needs_.occluders && old.needs_.occluders == needs_.occluders)
    take(occluders_, old.occluders_, "occluders");
  if (needs_.bvh && old.bvh_) {
    flat_ = std::move(old.flat_);
    take(bvh_, old.bvh_, "bvh");
    bvhTime_ = old.time_;
  }
}

void SceneResources::placeLights() {
  lights_ = scene_.lights;
  if (sampleLights_) {
    // Placeholder points (sample 0, seed 0) give the light count and types;
    // beginSample places them.
    for (const Light& l : emitters_->spotLights(emitterSequence(0, 0))) lights_.push_back(l);
    lightsKey_ = -1;
  }
}

void SceneResources::relight(Profiler& prof) {
  if (!gpu_) return;  // no GL lights (a CPU method reads the scene's)
  placeLights();
  if (!sampleLights_) uploadLights(prof);  // (else beginSample places and uploads the sample's lights)
}

void SceneResources::uploadLights(Profiler& prof) {
  gpu_->setLights(lights_);
  if (lightMaps_) {
    lightMaps_->setLights(lights_, *gpu_);
    lightMaps_->render(*gpu_, *shaders_, prof);
  }
  relightRadiance(prof);
}

void SceneResources::relightRadiance(Profiler& prof) {
  if (!atlas_ || !atlas_->hasRadiance()) return;
  insertRadiance(prof);
  valueTextures_->resolve(atlas_->valueBuffers(), *shaders_, prof);
}

void SceneResources::beginSample(int k, uint32_t seed, Profiler& prof) {
  if (!sampleLights_) return;
  const long long key = (static_cast<long long>(seed) << 31) | k;
  if (key == lightsKey_) return;
  lightsKey_ = key;
  lights_ = scene_.lights;
  for (const Light& l : emitters_->spotLights(emitterSequence(k, seed))) lights_.push_back(l);
  uploadLights(prof);
}

void SceneResources::insertRadiance(Profiler& prof) {
  atlas_->insertRadiance(
      time_,
      [this](unsigned program) {
        gpu_->bind(*shaders_, program);
        lightMaps_->bind();
      },
      prof);
}

void SceneResources::buildGrid(Profiler& prof) {
  const BinaryGridNeed& g = *needs_.binaryGrid;
  VoxelizeRequest vreq;
  vreq.scene = &scene_;
  vreq.box = box_;
  vreq.time = time_;
  vreq.threads = threads_;
  vreq.gl = gl_;
  vreq.shaders = shaders_;
  vreq.atlasCacheDir = defaultAtlasCacheDir();
  if (needs_.valueGrids) vreq.valueGrids = needs_.valueGrids->channels;
  voxelsCounted_ = false;
  if (!voxelizerStats_) voxelizerStats_ = std::make_unique<nlohmann::json>(nlohmann::json::object());
  if (gl_ && g.voxelizer == "atlas") {
    // The atlas voxelizer keeps the static meshes' grid on the GPU and re-inserts the dynamic ones.
    if (!atlas_) atlas_ = std::make_unique<AtlasVoxelizer>(vreq, prof);
    atlas_->voxelizeFrame(time_, prof);
    if (needs_.valueGrids) {
      if (!valueTextures_)
        valueTextures_ =
            std::make_unique<ValueTextures>(box_, needs_.valueGrids->channels, needs_.valueGrids->mips);
      // With area lights the radiance follows the sample's lights: beginSample inserts and resolves it.
      if (atlas_->hasRadiance() && !sampleLights_) insertRadiance(prof);
      valueTextures_->resolve(atlas_->valueBuffers(), *shaders_, prof);
    }
    if (!glPyramid_) glPyramid_ = std::make_unique<GlPyramid>(box_);
    auto s = prof.scope("pyramid");
    glPyramid_->build(atlas_->frameGrid(), *shaders_);
    return;
  }
  BinaryGrid grid = findVoxelizer(g.voxelizer).run(vreq, prof, *voxelizerStats_);
  if (gl_) {
    if (!glPyramid_) glPyramid_ = std::make_unique<GlPyramid>(box_);
    auto s = prof.scope("pyramid");
    glPyramid_->build(grid, *shaders_);
  } else {
    auto s = prof.scope("pyramid");
    cpuPyramid_ = std::make_unique<OrMipPyramid>(grid);
  }
}

namespace {
template <class T>
const T& need(const std::unique_ptr<T>& p, const char* what) {
  if (!p) fail("internal: a method read the ", what, " it did not declare in its needs");
  return *p;
}
}  // namespace

const Emitters& SceneResources::emitters() const { return need(emitters_, "area lights (before update)"); }
const std::vector<Light>& SceneResources::lights() const { return lights_; }
const GpuScene& SceneResources::gpuScene() const { return need(gpu_, "GPU scene"); }
const LightMaps& SceneResources::lightMaps() const { return need(lightMaps_, "light maps"); }
const GridBox& SceneResources::gridBox() const {
  if (!hasBox_) fail("internal: a method read the grid box without declaring a binary grid");
  return box_;
}
float SceneResources::voxelDiagonal() const { return glm::length(gridBox().voxelSize()); }
const GlPyramid& SceneResources::glPyramid() const { return need(glPyramid_, "GL pyramid"); }
const ValueTextures& SceneResources::valueTextures() const {
  return need(valueTextures_, "value-grid textures");
}
const OrMipPyramid& SceneResources::cpuPyramid() const { return need(cpuPyramid_, "CPU pyramid"); }
const EmbreeTracer& SceneResources::bvh() const { return need(bvh_, "BVH"); }
const Occluders& SceneResources::occluders() const { return need(occluders_, "occluders"); }
const FlatScene& SceneResources::flatScene() const { return need(flat_, "flattened scene"); }

std::vector<std::string> SceneResources::built() const {
  std::vector<std::string> n;
  if (lightMaps_) n.push_back(lightMaps_->reflective() ? "rsm" : "light_maps");
  if (glPyramid_ || cpuPyramid_) n.push_back("binary_grid");  // the pyramid's level 0
  if (valueTextures_) {
    n.push_back("value_grids");
    if (valueTextures_->mips() != ValueMips::None) n.push_back("value_mips");
  }
  if (glPyramid_ || cpuPyramid_) n.push_back("or_mip_pyramid");
  if (bvh_) n.push_back("bvh");
  if (occluders_) n.push_back("occluders");
  return n;
}

nlohmann::json SceneResources::gridStats() {
  if (!needs_.binaryGrid) return nullptr;
  if (!voxelsCounted_) {
    if (atlas_) *voxelizerStats_ = atlas_->stats();
    if (glPyramid_) {
      voxelsSet_ = glPyramid_->countLevel0();
    } else {
      const OrMipPyramid& p = *cpuPyramid_;
      const size_t end = p.levels() > 1 ? p.levelOffset(1) : p.words().size();
      voxelsSet_ = 0;
      for (size_t i = p.levelOffset(0); i < end; ++i)
        voxelsSet_ += uint64_t(__builtin_popcount(p.words()[i]));
    }
    voxelsCounted_ = true;
  }
  const glm::uvec3 r = needs_.binaryGrid->resolution;
  nlohmann::json j = {{"resolution", {r.x, r.y, r.z}},
                      {"voxelizer", needs_.binaryGrid->voxelizer},
                      {"voxels_set", voxelsSet_},
                      {"stats", *voxelizerStats_},
                      {"rebuilt_this_frame", rebuilt_}};
  if (valueTextures_) j["value_grids"] = valueTextures_->describe();
  return j;
}

nlohmann::json SceneResources::lightMapStats() const {
  if (!lightMaps_) return nullptr;
  return lightMaps_->describe();
}

}  // namespace vgi
