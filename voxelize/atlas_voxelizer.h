#pragma once
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "voxelize/gpu_grid.h"
#include "voxelize/value_grids.h"
#include "voxelize/value_textures.h"
#include "voxelize/voxelizer.h"

namespace vgi {

// Binary atlas voxelization on the GPU (VGI §3.1–3.2). Construction builds every
// mesh's atlas (cached), uploads the meshes in object space, measures which
// triangles own texels, and voxelizes the static meshes once. Each frame then
// copies the static grid and inserts only the dynamic meshes at that time.
// One mesh's atlas as rendered (read back for tests that run the CPU insertion).
struct AtlasSamples {
  std::vector<glm::vec4> positions;  // per texel: world position − grid origin, w = 1 if valid
  std::vector<int> triangles;        // per texel: the triangle that wrote it, −1 if none
  std::vector<glm::vec3> corners;    // corners − grid origin, 3 per triangle, at the frame's time
  float footprint = 0;               // world radius of each point's footprint (0: the point only)
};

class AtlasVoxelizer {
 public:
  // atlasPoints, if given, receives each mesh's atlas at request.time.
  AtlasVoxelizer(const VoxelizeRequest& request, Profiler& profiler,
                 std::vector<AtlasSamples>* atlasPoints = nullptr);
  ~AtlasVoxelizer();
  AtlasVoxelizer(const AtlasVoxelizer&) = delete;
  AtlasVoxelizer& operator=(const AtlasVoxelizer&) = delete;

  // Static grid → frame grid ("copy"; after the first frame only over the cells the dynamic
  // meshes could reach at the last frame's time), then the dynamic meshes at `time`
  // ("atlas_render", "insertion").
  void voxelizeFrame(float time, Profiler& profiler);
  const GpuGridBuffer& frameGrid() const { return *frame_; }
  BinaryGrid readFrame() const;
  // The multi-valued grids of the last frame (those the request asked for).
  ValueGrids readValues() const;
  // Their GL sum buffers, for ValueTextures::resolve (all 0 without value grids).
  ValueSumBuffers valueBuffers() const;

  // The radiance channel (requested in valueGrids): every mesh's atlas
  // rendered again at `time` with the diffuse direct light of the lights and
  // light maps `bindLights(program)` binds (SSBO BINDING_LIGHTS, the
  // TEXUNIT_LIGHT_* maps), into sums cleared first — after voxelizeFrame of
  // the same time, whose counts it shares. Two passes: the maximum (the
  // fixed-point range), then the insertion ("radiance_max", "radiance_insert").
  void insertRadiance(float time, const std::function<void(unsigned program)>& bindLights,
                      Profiler& profiler);
  bool hasRadiance() const { return radianceSums_ != 0; }

  // "points" (of the last frame, static included), "restored_cells" (the last frame's copy), "atlas_resolution",
  // "atlases" (per mesh), "triangles_without_texels", "static_meshes", "dynamic_meshes".
  nlohmann::json stats() const;
  // The GPU memory it holds: the static and frame grids, the value sums, the atlas targets, the meshes.
  double gpuBytes() const;

 private:
  struct MeshGpu;
  struct ValueBuffers;
  // Points are counted on the GPU into `counter` (read only by stats(): no sync per mesh).
  void renderAndInsert(const MeshGpu& mesh, float time, const GpuGridBuffer& target,
                       const ValueBuffers* values, unsigned counter, Profiler& profiler,
                       std::vector<int>* ids, AtlasSamples* points);
  void setPointCellInputs(unsigned program, const MeshGpu& mesh, float time) const;
  CellRange dynamicCells(float time) const;
  // The constructor's steps.
  void createPrograms();
  void createGrids();
  nlohmann::json addMesh(const struct Mesh& mesh, float texel, int maxTex, Profiler& profiler,
                         double& atlasMs);
  void uploadCorners(MeshGpu& mesh) const;
  void createTargets();
  glm::ivec2 insertStaticMeshes(Profiler& profiler, nlohmann::json& atlases,
                                std::vector<AtlasSamples>* atlasPoints);
  // Draws the mesh's atlas with `program` into the first `targets` attachments, its points through
  // `model` (object → offset from the grid's origin: modelToBox at a time; identity: object space).
  void renderAtlas(const MeshGpu& mesh, const glm::mat4& model, unsigned program, int targets) const;
  // A dynamic mesh's atlas in object space, drawn once into its own textures (MeshGpu::kept).
  void keepAtlas(MeshGpu& mesh, Profiler& profiler);
  VoxelizeRequest request_;
  std::vector<std::unique_ptr<MeshGpu>> meshes_;
  std::unique_ptr<GpuGridBuffer> static_, frame_;
  std::unique_ptr<ValueBuffers> staticValues_, frameValues_;
  std::unique_ptr<class GpuScene> materials_;  // material SSBO + textures, for multi-valued grids
  unsigned valueProg_ = 0, valueTargets_[3] = {0, 0, 0};
  unsigned renderProg_ = 0, insertProg_ = 0, fbo_ = 0, targets_[2] = {0, 0};
  unsigned staticCounter_ = 0, frameCounter_ = 0;
  unsigned radianceRenderProg_ = 0, radianceInsertProg_ = 0, radianceTarget_ = 0, radianceSums_ = 0,
           radianceMaxBuffer_ = 0;
  float radianceMax_ = 0;  // atlas points of the static meshes / this frame's dynamic ones
  int maxResolution_ = 0;
  bool framed_ = false;  // the frame grid holds a frame (at framedAt_)
  float framedAt_ = 0;
  uint64_t restoredCells_ = 0;
  nlohmann::json stats_;
};

// One-shot form for `vgi voxelize` and the registry: construct, one frame at
// request.time, read back; stats as AtlasVoxelizer::stats().
BinaryGrid voxelizeAtlasGl(const VoxelizeRequest& request, Profiler& profiler, nlohmann::json& stats,
                           std::vector<AtlasSamples>* atlasPoints = nullptr);

// The insertion step on the CPU, through the same kernels (shared::pointBit,
// shared::footprintCells, shared::triangleOverlapsBox).
void insertAtlasPoints(const AtlasSamples& atlas, BinaryGrid& grid);

}  // namespace vgi
