// vgi voxelize: build a binary voxel grid of a scene with one voxelizer and
// measure it against the exact one. The grid (and the multi-valued grids) are
// the framework's scene resources, declared as needs and built by
// SceneResources exactly as a method gets them (illum/resources/binary_grid.h,
// value_grids.h).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "apps/commands.h"
#include "core/build_info.h"
#include "core/error.h"
#include "core/gl_context.h"
#include "core/hash.h"
#include "core/output_files.h"
#include "core/scene_loader.h"
#include "core/shader_library.h"
#include "core/warnings.h"
#include "illum/framework/resources.h"
#include "illum/resources/binary_grid.h"
#include "illum/resources/value_grids.h"
#include "voxelize/atlas_voxelizer.h"
#include "voxelize/exact_voxelizer.h"
#include "voxelize/grid_metrics.h"
#include "voxelize/voxelizer.h"

namespace vgi::app {

namespace {

struct VoxelizeOptions {
  std::string scene = "builtin:cornell", voxels = "128", voxelizer = "atlas", stats, dump, gl = "auto",
              kind = "binary", textures = "none";
  float time = 0, texelsPerVoxel = kAutoTexelsPerVoxel, footprint = 1.0f, hybridCutoff = 4.0f;
  int threads = 0, atlasResolution = 0, frames = 1;
  float timeStep = 1.0f / 30.0f;
  bool noCache = false;
};

void addVoxelizeOptions(CLI::App* cmd, VoxelizeOptions& o) {
  cmd->add_option("--scene", o.scene, "builtin:cornell, a scene .json, or a model file")
      ->capture_default_str();
  cmd->add_option("--voxels", o.voxels, "N (N×N×N) or WxHxD; D = 128, 256, 512 or 1024")
      ->capture_default_str();
  std::string names;
  for (auto& v : voxelizerRegistry()) names += (names.empty() ? "" : "|") + v.name;
  cmd->add_option("--voxelizer", o.voxelizer, names)->capture_default_str();
  cmd->add_option("--kind", o.kind,
                  "grids to build: binary, plus any of normal,albedo,glossy,radiance (atlas; "
                  "comma-separated; radiance: diffuse direct light of the delta lights)")
      ->capture_default_str();
  cmd->add_option(
         "--textures", o.textures,
         "multi-valued grids also resolved into GL 3D textures (voxelize/value_textures.h): none, level0, "
         "isotropic or anisotropic mip chains (timed as value_resolve, value_mips)")
      ->capture_default_str();
  cmd->add_option("--time", o.time, "animation time")->capture_default_str();
  cmd->add_option("--threads", o.threads, "CPU threads (0 = all cores)")->capture_default_str();
  cmd->add_option("--gl", o.gl,
                  "GL backend: auto|egl|osmesa|zink (zink: GL on Vulkan on lavapipe, the second CPU driver)")
      ->capture_default_str();
  cmd->add_option("--texels-per-voxel", o.texelsPerVoxel, "atlas: texel = smallest voxel edge / this")
      ->capture_default_str();
  cmd->add_option("--atlas-resolution", o.atlasResolution,
                  "atlas: manual resolution per mesh (0 = automatic)")
      ->capture_default_str();
  cmd->add_option("--atlas-footprint", o.footprint,
                  "atlas: each point also sets the cells within this many texels that its triangle overlaps "
                  "(0 = the paper's single point)")
      ->capture_default_str();
  cmd->add_option("--hybrid-cutoff", o.hybridCutoff,
                  "hybrid: triangles whose area projected on their dominant plane is under this many cells^2 "
                  "are voxelized triangle-parallel")
      ->capture_default_str();
  cmd->add_flag("--no-cache", o.noCache, "atlas: do not read or write the atlas cache");
  cmd->add_option("--frames", o.frames,
                  "atlas: voxelize N frames from --time (static once, dynamic per frame)")
      ->capture_default_str();
  cmd->add_option("--time-step", o.timeStep, "time between frames")->capture_default_str();
  cmd->add_option("--stats", o.stats, "write the stats JSON here");
  cmd->add_option("--dump", o.dump, "write a picture of the grid (.png/.exr)");
}

// The options' ranges (each error names the option and the value).
void checkVoxelizeOptions(const VoxelizeOptions& o, const VoxelizerInfo& info) {
  if (o.threads < 0 || o.threads > 1024) fail("--threads ", o.threads, ": must be in [0, 1024]");
  if (!o.stats.empty()) checkOutputFile(o.stats, "--stats");
  if (!o.dump.empty()) checkOutputFile(o.dump, "--dump");
  if (!(o.texelsPerVoxel >= 0.25f && o.texelsPerVoxel <= 64.0f))
    fail("--texels-per-voxel ", o.texelsPerVoxel, ": must be in [0.25, 64]");
  if (o.atlasResolution < 0 || o.atlasResolution > 16384)
    fail("--atlas-resolution ", o.atlasResolution, ": must be in [0, 16384]");
  if (!(o.footprint >= 0.0f && o.footprint <= 4.0f))
    fail("--atlas-footprint ", o.footprint, ": must be in [0, 4] texels");
  if (!(o.hybridCutoff >= 0.0f && o.hybridCutoff <= 1e6f))
    fail("--hybrid-cutoff ", o.hybridCutoff, ": must be in [0, 1e6] cells^2");
  if (o.frames < 1 || o.frames > 100000) fail("--frames ", o.frames, ": must be in [1, 100000]");
  if (!std::isfinite(o.timeStep) || !std::isfinite(o.time))
    fail("--time ", o.time, " / --time-step ", o.timeStep, ": must be finite numbers");
  if (o.frames > 1 && info.name != "atlas") fail("--frames applies to --voxelizer atlas only");
  const std::vector<std::string> textureKinds = {"none", "level0", "isotropic", "anisotropic"};
  if (std::find(textureKinds.begin(), textureKinds.end(), o.textures) == textureKinds.end())
    fail("--textures '", o.textures, "': must be none, level0, isotropic or anisotropic");
}

// The grid the options ask for: the voxelizer with its settings and the value channels of --kind.
BinaryGridNeed gridNeed(const VoxelizeOptions& o, const VoxelizerInfo& info) {
  BinaryGridNeed g;
  g.resolution = parseResolution(o.voxels);
  checkGridMemory(g.resolution, info.name == "exact" ? 1 : 2);
  g.voxelizer = info.name;
  g.texelsPerVoxel = o.texelsPerVoxel;
  g.atlasResolution = o.atlasResolution;
  g.atlasFootprint = o.footprint;
  g.hybridCutoff = o.hybridCutoff;
  g.atlasCache = !o.noCache;
  g.gridCache = false;  // vgi voxelize measures the voxelizer: it always runs
  std::string kinds = o.kind;
  if (kinds == "binary")
    kinds.clear();
  else if (kinds.rfind("binary,", 0) == 0)
    kinds = kinds.substr(7);
  if (!kinds.empty()) {
    g.values = parseValueChannels(kinds);
    if (info.name != "atlas")
      fail("--kind ", o.kind, ": multi-valued grids are built by --voxelizer atlas only");
  }
  if (o.textures != "none" && g.values.empty())
    fail("--textures ", o.textures, ": needs multi-valued grids (--kind binary,normal,…)");
  return g;
}

// The grid and, for --textures or the radiance channel (its direct light comes from 1024² light maps of
// the scene's delta lights), the value grids over it.
SceneNeeds voxelizeNeeds(const VoxelizeOptions& o, const BinaryGridNeed& grid) {
  SceneNeeds n;
  n.add(grid);
  const bool radiance = std::find(grid.values.begin(), grid.values.end(), "radiance") != grid.values.end();
  if (o.textures != "none" || radiance) {
    ValueGridNeed v;
    v.grid = grid;
    v.mips = o.textures == "isotropic"     ? ValueMips::Isotropic
             : o.textures == "anisotropic" ? ValueMips::Anisotropic
                                           : ValueMips::None;
    if (radiance) v.lightMaps = LightMapNeed{1024, false};
    n.add(v);
  }
  return n;
}

// Every frame of the run through the resources; per-frame timings when there are several, whose sum is
// the run's.
nlohmann::json updateFrames(const VoxelizeOptions& o, SceneResources& res, Profiler& prof, bool gpu,
                            nlohmann::json& frames) {
  if (o.frames == 1) {
    res.update(o.time, prof);
    prof.resolve(true);
    return prof.timingsMs();
  }
  nlohmann::json sum = nlohmann::json::object();
  for (int i = 0; i < o.frames; ++i) {
    const float t = o.time + float(i) * o.timeStep;
    Profiler frameProf(gpu);
    res.update(t, frameProf);
    frameProf.resolve(true);
    const nlohmann::json ms = frameProf.timingsMs();
    frames.push_back({{"time", t}, {"timings_ms", ms}, {"total_ms", frameProf.totalMs()}});
    for (auto& [pass, v] : ms.items()) sum[pass] = sum.value(pass, 0.0) + v.get<double>();
  }
  return sum;
}

nlohmann::json vec(glm::vec3 v) { return {v.x, v.y, v.z}; }

// The grid against the exact voxelizer's at the same box and time: recall, precision, holes, extra, and
// recall against the cells more than grazed (see docs/BENCHMARKS.md).
void addGridQuality(nlohmann::json& s, const BinaryGrid& grid, const Scene& scene, const GridBox& box,
                    float time, const VoxelizeOptions& o, bool exact) {
  const GridComparison cmp =
      exact ? compareGrids(grid, grid) : compareGrids(grid, voxelizeExact(scene, box, time, o.threads));
  const GridComparison interior =
      compareGrids(grid, voxelizeExact(scene, box, time, o.threads, kInteriorShrink));
  s["voxels_set"] = grid.count();
  s["recall"] = cmp.recall();
  s["precision"] = cmp.precision();
  s["holes"] = cmp.holes();
  s["extra"] = cmp.extra();
  s["exact_voxels"] = cmp.exact;
  s["recall_interior"] = interior.recall();
  s["interior_shrink_cells"] = kInteriorShrink;
  s["box"] = {{"origin", vec(box.origin)},
              {"extent", vec(box.extent)},
              {"axes", {vec(box.axes[0]), vec(box.axes[1]), vec(box.axes[2])}}};
  s["voxel_size"] = vec(box.voxelSize());
}

void runVoxelize(const VoxelizeOptions& o) {
  const VoxelizerInfo& info = findVoxelizer(o.voxelizer);
  checkVoxelizeOptions(o, info);
  const BinaryGridNeed grid = gridNeed(o, info);
  Scene scene = loadScene(o.scene);
  printWarnings(scene.report.warnings);
  const bool gpu = info.needsGl || !grid.values.empty();
  std::unique_ptr<GlContext> gl;
  std::unique_ptr<ShaderLibrary> shaders;
  if (gpu) {
    gl = GlContext::create(parseGlBackend(o.gl));
    shaders = std::make_unique<ShaderLibrary>();
  }
  std::vector<float> times;
  for (int i = 0; i < o.frames; ++i) times.push_back(o.time + float(i) * o.timeStep);
  const float last = times.back();
  SceneResources res(scene, voxelizeNeeds(o, grid), gl.get(), shaders.get(), times, o.threads);
  res.needs().check("voxelize", gpu);
  Profiler prof(gpu);
  nlohmann::json s, frames = nlohmann::json::array();
  nlohmann::json timings = updateFrames(o, res, prof, gpu, frames);
  BinaryGrid result(res.get<GridBox>());
  ValueGrids values;
  Profiler readback(gpu);
  if (AtlasVoxelizer* atlas = res.tryGet<AtlasVoxelizer>()) {
    auto sc = readback.scope("readback");
    result = atlas->readFrame();
    values = atlas->readValues();
  } else {
    result = res.get<BinaryGrid>();
  }
  readback.resolve(true);
  const nlohmann::json readbackMs = readback.timingsMs();
  for (auto& [pass, v] : readbackMs.items()) timings[pass] = timings.value(pass, 0.0) + v.get<double>();
  nlohmann::json extra;
  res.addStats(extra);
  s.update(extra["grid"]["stats"]);
  if (o.textures != "none") {
    s["value_textures"] = extra["value_grids"];
    s["value_textures"].erase("rebuilt_this_frame");
  }
  if (o.frames > 1) s["frames"] = frames;
  s["built"] = nlohmann::json::array({"binary"});
  for (auto& ch : grid.values) s["built"].push_back(ch);
  if (!grid.values.empty()) s["value_grids"] = values.summary();
  if (gl && gl->errorCount() > 0)
    fail("voxelizer '", info.name, "' raised ", gl->errorCount(), " GL error(s)");
  addGridQuality(s, result, scene, res.get<GridBox>(), last, o, info.name == "exact");
  s["voxelizer"] = info.name;
  s["voxels_set"] = result.count();
  s["grid_digest"] = hexDigest(result.digest());
  s["scene"] = o.scene;
  s["resolution"] = {grid.resolution.x, grid.resolution.y, grid.resolution.z};
  if (!s.contains("points")) s["points"] = nullptr;
  if (!s.contains("atlas_resolution")) s["atlas_resolution"] = nullptr;
  double total = 0;
  for (auto& [pass, v] : timings.items()) total += v.get<double>();
  s["timings_ms"] = timings;
  s["total_ms"] = total;
  s["gl_renderer"] = gl ? gl->renderer() : "none (CPU voxelizer)";
  s["triangles"] = scene.triangleCount();
  s["git_revision"] = gitRevision();
  if (!o.dump.empty()) {
    writeGridPicture(result, o.dump);
    // One picture per value grid beside it: NAME_normal.png, …
    const std::string stem = o.dump.substr(0, o.dump.find_last_of('.'));
    const std::string ext = o.dump.substr(o.dump.find_last_of('.'));
    for (auto& ch : grid.values) writeValuePicture(values, ch, stem + "_" + ch + ext);
  }
  if (!o.stats.empty()) writeJsonFile(s, o.stats);
  std::printf("%s %ux%ux%u: %llu voxels set, recall %.5f (interior %.5f), precision %.5f, %.1f ms\n",
              info.name.c_str(), grid.resolution.x, grid.resolution.y, grid.resolution.z,
              (unsigned long long)result.count(), s["recall"].get<double>(),
              s["recall_interior"].get<double>(), s["precision"].get<double>(), total);
}

}  // namespace

void addVoxelizeCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "voxelize", "Voxelize a scene into a binary grid and compare it with the exact voxelizer");
  auto o = std::make_shared<VoxelizeOptions>();
  addVoxelizeOptions(cmd, *o);
  cmd->callback([o] { runVoxelize(*o); });
}

}  // namespace vgi::app
