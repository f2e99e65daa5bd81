// What a method needs of a scene, as a typed declaration, and the one object
// that builds exactly that and keeps it across the frames of an animation.
//
// A method states its needs from its resolved parameters (Method::needs());
// the render job makes one SceneResources per run and calls update(time)
// before each frame: the first call builds everything; later calls, for a
// scene with dynamic meshes, update only what moves (the GPU scene's
// vertices, the dynamic meshes' voxels — the atlas voxelizer keeps the static
// meshes' grid, VGI §3.2 —, the pyramid, the light maps, the BVH). Static
// scenes build once. Area lights (core/emitters.h) come with every method:
// the CPU methods sample them from emitters(); for the GL methods
// beginSample(k) turns one emitter point per sample into spot lights, so the
// G-buffer's lights and the light maps change per sample (the light maps are
// then a per-sample pass). built() names what was actually allocated, so the
// stats, `vgi compare` and the registry tests read facts, not declarations.
#pragma once
#include <glm/glm.hpp>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "voxelize/value_textures.h"
#include "voxelize/voxel_grid.h"

namespace vgi {

class AtlasVoxelizer;
class Emitters;
struct Light;
class EmbreeTracer;
class GlContext;
class GlPyramid;
class GpuScene;
class LightMaps;
class Occluders;
class OrMipPyramid;
class ParamSet;
class Profiler;
struct Scene;
class ShaderLibrary;
struct FlatScene;

struct LightMapNeed {
  int resolution = 1024;
  bool reflective = false;  // reflective shadow maps (position, normal, flux) for VGI §5.1
};

struct BinaryGridNeed {
  glm::uvec3 resolution{128};
  std::string voxelizer = "atlas";  // a name of voxelizerRegistry()
  // Cubic cells (cone tracing: a mip level's texel is a cube of 2^l cells):
  // the fitted box grows about its centre along the shorter axes.
  bool cubicCells = false;
};

// Multi-valued grids as 3D textures (voxelize/value_textures.h) over the
// binary grid's box: built by the atlas voxelizer's insertion, so they need
// binaryGrid with voxelizer "atlas" (its points are where the values come from).
struct ValueGridNeed {
  std::vector<std::string>
      channels;  // of valueChannelNames(): normal, albedo, glossy, radiance (needs lightMaps)
  ValueMips mips = ValueMips::None;
};

// The scene simplified for passes that draw it many times for its occlusion
// only (illum/occluders.h): about `triangles` triangles, no point of the scene
// farther than `tolerance` (world units) from them; within the budget, the scene as it is.
struct OccluderNeed {
  size_t triangles = 8192;
  float tolerance = 0.0f;
  bool operator==(const OccluderNeed& o) const {
    return triangles == o.triangles && tolerance == o.tolerance;
  }
};

// The resources one render of a method uses. GL methods get GL resources (the
// grid voxelized into GPU memory, a GPU pyramid); CPU methods get host ones.
struct SceneNeeds {
  bool gbuffer = false;                   // GL: the per-pixel G-buffer (a render target of the image size)
  std::optional<LightMapNeed> lightMaps;  // GL: shadow maps / RSMs of every delta light
  std::optional<BinaryGridNeed> binaryGrid;
  std::optional<ValueGridNeed> valueGrids;  // GL: the channels' 3D textures (+ mips)
  bool orMipPyramid = false;                // over binaryGrid (required with it on GL: GLSL reads level 0)
  bool bvh = false;                         // CPU: the flattened scene in an Embree BVH
  std::optional<OccluderNeed> occluders;    // GL: the simplified scene (illum/occluders.h)

  // The resource names of the stats ("gbuffer", "light_maps" or "rsm",
  // "binary_grid", "value_grids", "value_mips", "or_mip_pyramid", "bvh", "occluders"), in that order.
  std::vector<std::string> names() const;
  // The same resources, built the same way (a render job keeps its resources when they are).
  bool operator==(const SceneNeeds& o) const;
  // Throws if the combination cannot be built (a pyramid without a grid, …),
  // naming `method`.
  void check(const std::string& method, bool gl) const;
};

// The `voxels` (N or WxHxD) and `voxelizer` parameters of a module that
// traces a binary grid; `grids`: how many grid-sized buffers it keeps (the
// memory check).
BinaryGridNeed readBinaryGridParams(ParamSet& params, int grids, bool atlasOnly = false,
                                    const std::string& defaultVoxelizer = "atlas");

class SceneResources {
 public:
  // gl/shaders: set for a GL method (then GL resources are made), null for a CPU one.
  SceneResources(const Scene& scene, SceneNeeds needs, GlContext* gl, ShaderLibrary* shaders,
                 std::vector<float> frameTimes, int threads);
  ~SceneResources();
  SceneResources(const SceneResources&) = delete;
  SceneResources& operator=(const SceneResources&) = delete;

  // Makes the resources current for animation time `time` (see above); returns
  // whether anything was (re)built.
  bool update(float time, Profiler& profiler);
  // The scene's delta lights moved (same count and types): the next update
  // uploads them and renders again what depends on them — the light maps and
  // the atlas grid's radiance — keeping the grid and the pyramid.
  void lightsChanged() { lightsChanged_ = true; }
  // Takes over from `old` (the same scene, context and frame times; nothing
  // built here yet) what these needs build the same way, so that a method
  // switch or a parameter change rebuilds only what differs: the GPU scene,
  // the light maps (same resolution and kind), the grid with its pyramid and
  // value grids (the same grid, value-grid and pyramid needs; the atlas grid's
  // radiance is inserted again for these light maps), the BVH and the
  // occluders (the same budget). What is
  // taken is listed by adopted(); `old` keeps the rest, to be dropped.
  void adopt(SceneResources& old);
  const std::vector<std::string>& adopted() const { return adopted_; }

  const SceneNeeds& needs() const { return needs_; }

  // Before sample k of a run seeded `seed`: with area lights and GL lights
  // (G-buffer or light maps declared), the lights become the scene's delta
  // lights plus the spot lights of emitter point emitterSequence(k, seed),
  // uploaded, and the light maps are rendered for them. No-op otherwise.
  void beginSample(int k, uint32_t seed, Profiler& profiler);
  // The area lights at the current time (every method may read them).
  const Emitters& emitters() const;
  // The lights the GL programs see now (see beginSample).
  const std::vector<Light>& lights() const;

  // Each throws if the method did not declare it (a module reads only what it
  // asked for, so `built` stays true).
  const GpuScene& gpuScene() const;
  const LightMaps& lightMaps() const;
  bool hasLightMaps() const { return bool(lightMaps_); }  // built (at the first update)
  const GridBox& gridBox() const;  // the grid's box: the union of the animation's bounds
  float voxelDiagonal() const;
  const GlPyramid& glPyramid() const;
  const ValueTextures& valueTextures() const;
  const OrMipPyramid& cpuPyramid() const;
  const EmbreeTracer& bvh() const;
  const Occluders& occluders() const;
  const FlatScene& flatScene() const;  // the triangles the BVH holds

  // What was allocated, as SceneNeeds::names() spells it (the G-buffer, a
  // render target, is the sample loop's: it adds that name).
  std::vector<std::string> built() const;
  // The grid's stats (resolution, voxelizer, voxels set, the voxelizer's own)
  // and the light maps'; null where absent.
  nlohmann::json gridStats();  // counts the set voxels once per build (a read-back: call it after the image)
  nlohmann::json lightMapStats() const;

 private:
  void buildGrid(Profiler& profiler);
  void insertRadiance(Profiler& profiler);  // the atlas voxelizer's radiance pass with these lights
  void placeLights();                       // lights_: the scene's, plus the area lights' placeholders
  void relight(Profiler& profiler);         // after lightsChanged()
  void uploadLights(Profiler& profiler);  // lights_ to the GPU scene; the light maps and radiance they light
  void relightRadiance(Profiler& profiler);  // the atlas grid's radiance (if any) for the light maps now
  const Scene& scene_;
  SceneNeeds needs_;
  GlContext* gl_;
  ShaderLibrary* shaders_;
  std::vector<float> frameTimes_;
  int threads_;
  bool first_ = true, rebuilt_ = false, lightsChanged_ = false;
  std::vector<std::string> adopted_;
  std::optional<float> gridTime_, bvhTime_;  // when adopted: the time they were built for
  float time_ = 0;

  std::unique_ptr<Emitters> emitters_;
  std::vector<Light> lights_;
  bool sampleLights_ = false;  // lights_ follow the sample (area lights on GL resources)
  long long lightsKey_ = -1;   // (seed, k) of the lights uploaded; −1: none yet
  std::unique_ptr<GpuScene> gpu_;
  std::unique_ptr<LightMaps> lightMaps_;
  GridBox box_;
  bool hasBox_ = false;
  std::unique_ptr<AtlasVoxelizer> atlas_;  // holds the static meshes' grid between frames
  std::unique_ptr<GlPyramid> glPyramid_;
  std::unique_ptr<ValueTextures> valueTextures_;
  std::unique_ptr<OrMipPyramid> cpuPyramid_;
  std::unique_ptr<FlatScene> flat_;
  std::unique_ptr<EmbreeTracer> bvh_;
  std::unique_ptr<Occluders> occluders_;
  uint64_t voxelsSet_ = 0;
  bool voxelsCounted_ = false;
  std::unique_ptr<nlohmann::json> voxelizerStats_;
};

}  // namespace vgi
