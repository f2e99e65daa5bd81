// `vgi bench traverse`: experiments/traverse_bench.h.
#include "experiments/traverse_bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include "core/build_info.h"
#include "core/error.h"
#include "core/gl_context.h"
#include "core/json_text.h"
#include "core/parallel.h"
#include "core/params.h"
#include "core/profiler.h"
#include "core/scene_loader.h"
#include "core/shader_library.h"
#include "core/warnings.h"
#include "traverse/embree_tracer.h"
#include "traverse/gl_ray_tracer.h"
#include "traverse/gpu_bvh.h"
#include "traverse/or_mip_pyramid.h"
#include "traverse/ray_population.h"
#include "traverse/ray_tracers.h"
#include "voxelize/atlas.h"
#include "voxelize/setup_cache.h"
#include "voxelize/voxelizer.h"

namespace vgi {

namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

float parseMaxDist(const std::string& s) {
  if (s == "inf") return INFINITY;
  float v = 0;
  try {
    size_t used = 0;
    v = std::stof(s, &used);
    if (used != s.size()) throw std::invalid_argument(s);
  } catch (const std::exception&) {
    fail("--max-dist '", s, "': expected a number (fraction of the scene diagonal) or 'inf'");
  }
  if (!(v > 0.0f) || !std::isfinite(v)) fail("--max-dist ", s, ": must be > 0 (or 'inf')");
  return v;
}

// Agreement of `r` with a reference result set.
struct Agreement {
  double sameHit = 0, sameVoxel = 0, errMean = 0, errP95 = 0, errMax = 0;
  size_t bothHit = 0;
};

Agreement agreement(const std::vector<TraceResult>& r, const std::vector<TraceResult>& ref, float voxelSize) {
  Agreement a;
  std::vector<float> errs;
  size_t sameHit = 0, sameVoxel = 0;
  const float tol = 1e-5f * voxelSize;
  for (size_t i = 0; i < r.size(); ++i) {
    if (r[i].hit != ref[i].hit) continue;
    ++sameHit;
    if (!r[i].hit) {
      ++sameVoxel;
      continue;
    }
    if (r[i].voxel == ref[i].voxel && std::abs(r[i].t - ref[i].t) <= tol) ++sameVoxel;
    errs.push_back(std::abs(r[i].t - ref[i].t) / voxelSize);
  }
  a.sameHit = r.empty() ? 1.0 : double(sameHit) / double(r.size());
  a.sameVoxel = r.empty() ? 1.0 : double(sameVoxel) / double(r.size());
  a.bothHit = errs.size();
  if (!errs.empty()) {
    double sum = 0;
    for (float e : errs) sum += e;
    a.errMean = sum / double(errs.size());
    std::sort(errs.begin(), errs.end());
    a.errP95 = errs[std::min(errs.size() - 1, size_t(0.95 * double(errs.size())))];
    a.errMax = errs.back();
  }
  return a;
}

// The mean and the 99th percentile of one count over the rays.
nlohmann::json meanAndP99(std::vector<uint32_t> v) {
  if (v.empty()) return {{"mean", 0.0}, {"p99", 0}};
  double sum = 0;
  for (uint32_t x : v) sum += x;
  const size_t k = std::min(v.size() - 1, size_t(0.99 * double(v.size())));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return {{"mean", sum / double(v.size())}, {"p99", v[k]}};
}

// What each ray of a shared kernel costs a GPU, device-independent: loop steps, memory loads and their
// bytes, levels climbed and refined (the C++ build of the kernel the GLSL runs, on the same rays).
nlohmann::json traversalCounts(const RayTracer& tracer, const std::vector<TraceRay>& rays, int threads) {
  std::vector<TraceResult> r;
  std::vector<shared::TraceCounts> c;
  tracer.countBatch(rays, r, c, threads);
  auto column = [&](auto field) {
    std::vector<uint32_t> v(rays.size());
    for (size_t i = 0; i < rays.size(); ++i) v[i] = field(i);
    return meanAndP99(std::move(v));
  };
  return {{"steps", column([&](size_t i) { return r[i].steps; })},
          {"fetches", column([&](size_t i) { return c[i].fetches; })},
          {"bytes", column([&](size_t i) { return c[i].bytes; })},
          {"climbs", column([&](size_t i) { return c[i].climbs; })},
          {"refines", column([&](size_t i) { return c[i].refines; })}};
}

// What every ray length traces: the grid and its pyramid, and the triangles (Embree, our BVH), on
// the CPU and, unless --no-gl, on the GPU.
struct TraverseSetup {
  Scene scene;
  FlatScene flat;
  GridBox box;
  std::unique_ptr<OrMipPyramid> pyramid;
  std::unique_ptr<EmbreeTracer> embree;
  BvhArrays bvh;
  std::unique_ptr<GlContext> gl;
  std::unique_ptr<ShaderLibrary> shaders;
  std::unique_ptr<GlPyramid> gpuPyramid;
  std::unique_ptr<GpuBvh> gpuBvh;
  nlohmann::json build = nlohmann::json::object();  // the structures' sizes and build times
};

TraverseSetup setupTraverse(const TraverseBenchOptions& o, const VoxelizerInfo& vox, glm::uvec3 res) {
  TraverseSetup t;
  t.scene = loadScene(o.scene);
  printWarnings(t.scene.report.warnings);
  t.flat = flatten(t.scene);
  if (vox.needsGl || !o.noGl) {
    t.gl = GlContext::create(parseGlBackend(o.gl));
    t.shaders = std::make_unique<ShaderLibrary>();
  }
  VoxelizeRequest req;
  req.scene = &t.scene;
  req.box = t.box = fitGridBox(t.scene, res);
  req.threads = o.threads;
  req.atlasCacheDir = defaultSetupCacheDir();
  req.gl = t.gl.get();
  req.shaders = t.shaders.get();
  Profiler buildProf(t.gl != nullptr);
  nlohmann::json voxStats;
  BinaryGrid grid = vox.run(req, buildProf, voxStats);
  auto t0 = std::chrono::steady_clock::now();
  t.pyramid = std::make_unique<OrMipPyramid>(grid);
  t.build["pyramid_build_cpu_ms"] = msSince(t0);
  t0 = std::chrono::steady_clock::now();
  t.embree = std::make_unique<EmbreeTracer>(t.flat);
  t.build["embree_build_ms"] = msSince(t0);
  t0 = std::chrono::steady_clock::now();
  BvhBuildOptions bvhOptions;
  bvhOptions.width = o.bvhWidth;
  t.bvh = buildBvh(t.flat, bvhOptions);
  t.build["bvh_build_ms"] = msSince(t0);
  t.build["bvh"] = t.bvh.describe();
  buildProf.resolve(true);
  t.build["voxelizer_stats"] = {{"voxels_set", grid.count()}, {"timings_ms", buildProf.timingsMs()}};
  t.build["pyramid_levels"] = t.pyramid->levels();
  if (!o.noGl) {
    t.gpuPyramid = std::make_unique<GlPyramid>(*t.pyramid);
    t.gpuBvh = std::make_unique<GpuBvh>(t.bvh);
  }
  return t;
}

// One ray length: every tracer on the CPU (the fastest of --repeat runs) and in GLSL, each against
// the DDA oracle and Embree's exact hits.
nlohmann::json benchRayLength(TraverseSetup& t, const TraverseBenchOptions& o,
                              std::vector<std::string> tracers, float maxDist, int threads) {
  const glm::vec3 vs = t.box.voxelSize();
  const float voxelSize = (vs.x + vs.y + vs.z) / 3.0f;  // "voxel sizes" in the error columns
  RayPopulation pop;
  pop.count = o.rays;
  pop.seed = o.seed;
  pop.tmax = std::isinf(maxDist) ? INFINITY : maxDist * glm::length(t.box.extent);
  pop.offset = o.offset * glm::length(vs);
  pop.viewpoint = t.scene.camera.position;
  const std::vector<TraceRay> rays = surfaceRays(t.flat, pop);
  TracerInputs in;
  in.pyramid = t.pyramid.get();
  in.embree = t.embree.get();
  in.bvh = &t.bvh;
  std::map<std::string, std::vector<TraceResult>> results;
  std::map<std::string, double> cpuMs, glMs;
  std::map<std::string, bool> glMatchesCpu;
  std::map<std::string, nlohmann::json> counts;
  for (const std::string& name : {std::string("dda"), std::string("embree")})  // the references, always run
    if (std::find(tracers.begin(), tracers.end(), name) == tracers.end()) tracers.push_back(name);
  for (const std::string& name : tracers) {
    auto tracer = createTracer(name, in);
    double best = 1e300;
    for (int i = 0; i < o.repeat; ++i) {
      auto t1 = std::chrono::steady_clock::now();
      tracer->traceBatch(rays, results[name], threads);
      best = std::min(best, msSince(t1));
    }
    cpuMs[name] = best;
    if (name != "embree") counts[name] = traversalCounts(*tracer, rays, threads);
    if (o.noGl || !findTracer(name).glsl) continue;
    Profiler warm(true), prof(true);
    traceRaysGl(*t.gpuPyramid, *t.shaders, name, std::vector<TraceRay>(rays.begin(), rays.begin() + 1), warm,
                0, t.gpuBvh.get());
    std::vector<TraceResult> r = traceRaysGl(*t.gpuPyramid, *t.shaders, name, rays, prof, 0, t.gpuBvh.get());
    prof.resolve(true);
    glMs[name] = prof.timingsMs()["trace_" + name].get<double>();
    bool same = true;
    const auto& c = results[name];
    for (size_t i = 0; i < r.size() && same; ++i)
      same = r[i].hit == c[i].hit && r[i].steps == c[i].steps &&
             (!r[i].hit || (r[i].t == c[i].t && r[i].voxel == c[i].voxel));
    glMatchesCpu[name] = same;
  }
  if (t.gl && t.gl->errorCount() > 0) fail("bench traverse: ", t.gl->errorCount(), " GL error(s)");
  nlohmann::json per = nlohmann::json::object();
  for (const std::string& name : tracers) {
    const auto& r = results[name];
    Agreement dda = agreement(r, results["dda"], voxelSize);
    Agreement emb = agreement(r, results["embree"], voxelSize);
    size_t hits = 0;
    uint64_t steps = 0;
    for (auto& x : r) {
      hits += x.hit;
      steps += x.steps;
    }
    nlohmann::json j;
    j["mrays_per_s"] = double(rays.size()) / (cpuMs[name] * 1e3);
    j["cpu_ms"] = cpuMs[name];
    if (glMs.count(name)) {
      j["gl_mrays_per_s"] = double(rays.size()) / (glMs[name] * 1e3);
      j["gl_ms"] = glMs[name];
      j["gl_equals_cpu"] = glMatchesCpu[name];
    }
    j["hit_rate"] = double(hits) / double(rays.size());
    j["mean_steps"] = double(steps) / double(rays.size());
    j["agree_dda"] = dda.sameVoxel;
    j["agree_dda_hit"] = dda.sameHit;
    j["agree_embree_hit"] = emb.sameHit;
    j["dist_err_mean_voxels"] = emb.errMean;
    j["dist_err_p95_voxels"] = emb.errP95;
    j["dist_err_max_voxels"] = emb.errMax;
    if (counts.count(name)) j["counts"] = counts[name];
    per[name] = j;
  }
  return {{"max_dist", std::isinf(maxDist) ? nlohmann::json("inf") : nlohmann::json(maxDist)},
          {"max_dist_world", std::isinf(pop.tmax) ? nlohmann::json("inf") : nlohmann::json(pop.tmax)},
          {"offset_world", pop.offset},
          {"voxel_size", voxelSize},
          {"rays", rays.size()},
          {"tracers", per}};
}

// Where the GLSL hierarchical tracer stops being faster than the GLSL BVH as the rays grow: the
// ratio of their rays per second interpolated in log(length) between the lengths around 1; null
// when it does not cross 1 inside the lengths measured (or a tracer did not run in GLSL).
nlohmann::json crossover(const nlohmann::json& lengths) {
  double prevL = 0, prevR = 0;
  bool have = false;
  for (auto& l : lengths) {
    const auto& tr = l["tracers"];
    if (!l["max_dist"].is_number() || !tr.contains("hierarchical") || !tr.contains("bvh") ||
        !tr["hierarchical"].contains("gl_mrays_per_s") || !tr["bvh"].contains("gl_mrays_per_s"))
      continue;
    const double len = l["max_dist"].get<double>();
    const double r =
        tr["hierarchical"]["gl_mrays_per_s"].get<double>() / tr["bvh"]["gl_mrays_per_s"].get<double>();
    if (have && (prevR - 1.0) * (r - 1.0) <= 0.0 && prevR != r) {
      const double f = (1.0 - prevR) / (r - prevR);
      return std::exp(std::log(prevL) + f * (std::log(len) - std::log(prevL)));
    }
    prevL = len, prevR = r, have = true;
  }
  return nullptr;
}

// A ray length as the tables print it: 0.1, 2.53, inf (the JSON holds the float's double).
std::string lengthText(const nlohmann::json& v) {
  if (!v.is_number()) return v.is_string() ? v.get<std::string>() : v.dump();
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", double(float(v.get<double>())));
  return buf;
}

void printTraverse(const nlohmann::json& s) {
  const auto& r = s["resolution"];
  std::printf("%s, %dx%dx%d (%s), %zu rays per length, %d threads, %s\n",
              s["scene"].get<std::string>().c_str(), r[0].get<int>(), r[1].get<int>(), r[2].get<int>(),
              s["voxelizer"].get<std::string>().c_str(), s["lengths"][0]["rays"].get<size_t>(),
              s["threads"].get<int>(), s["gl_renderer"].get<std::string>().c_str());
  for (auto& l : s["lengths"]) {
    std::printf("max-dist %s x diagonal (%s world)\n", lengthText(l["max_dist"]).c_str(),
                lengthText(l["max_dist_world"]).c_str());
    std::printf("%-13s %10s %10s %8s %9s %10s %10s %10s\n", "tracer", "Mrays/s", "GL Mrays/s", "hits",
                "agree_dda", "agree_emb", "err_mean", "err_p95");
    for (auto& [name, j] : l["tracers"].items()) {
      char glRate[32] = "-";
      if (j.contains("gl_mrays_per_s"))
        std::snprintf(glRate, sizeof glRate, "%.3f", j["gl_mrays_per_s"].get<double>());
      std::printf("%-13s %10.3f %10s %8.4f %9.5f %10.5f %10.3f %10.3f\n", name.c_str(),
                  j["mrays_per_s"].get<double>(), glRate, j["hit_rate"].get<double>(),
                  j["agree_dda"].get<double>(), j["agree_embree_hit"].get<double>(),
                  j["dist_err_mean_voxels"].get<double>(), j["dist_err_p95_voxels"].get<double>());
    }
  }
  for (auto& l : s["lengths"]) {
    std::printf("per ray at max-dist %s x diagonal (the C++ build of each GLSL kernel): mean / p99\n",
                lengthText(l["max_dist"]).c_str());
    std::printf("%-13s %15s %15s %15s %15s %15s\n", "tracer", "steps", "fetches", "bytes", "climbs",
                "refines");
    for (auto& [name, j] : l["tracers"].items()) {
      if (!j.contains("counts")) continue;
      std::printf("%-13s", name.c_str());
      for (const char* k : {"steps", "fetches", "bytes", "climbs", "refines"})
        std::printf(" %8.2f / %4u", j["counts"][k]["mean"].get<double>(),
                    j["counts"][k]["p99"].get<unsigned>());
      std::printf("\n");
    }
  }
  if (s.contains("crossover_max_dist"))
    std::printf("GLSL hierarchical / bvh crossover: %s x diagonal\n", s["crossover_max_dist"].dump().c_str());
}

}  // namespace

nlohmann::json runTraverseBench(const TraverseBenchOptions& o) {
  if (o.threads < 0 || o.threads > 1024) fail("--threads ", o.threads, ": must be in [0, 1024]");
  if (o.rays < 1 || o.rays > 100000000) fail("--rays ", o.rays, ": must be in [1, 100000000]");
  if (o.repeat < 1 || o.repeat > 100) fail("--repeat ", o.repeat, ": must be in [1, 100]");
  if (!(o.offset >= 0.0f && o.offset <= 100.0f)) fail("--offset ", o.offset, ": must be in [0, 100]");
  std::vector<float> lengths;
  for (auto& l : splitList(o.maxDist)) lengths.push_back(parseMaxDist(l));
  if (lengths.empty()) fail("--max-dist '", o.maxDist, "': empty list");
  const std::vector<std::string> tracers = splitList(o.tracers);
  if (tracers.empty()) fail("--tracers '", o.tracers, "': empty list");
  for (auto& t : tracers) findTracer(t, "--tracers");
  const VoxelizerInfo& vox = findVoxelizer(o.voxelizer);
  const glm::uvec3 res = parseResolution(o.voxels);
  checkGridMemory(res, 2);
  TraverseSetup setup = setupTraverse(o, vox, res);
  const int threads = resolveThreads(o.threads);
  nlohmann::json s;
  s["bench"] = "traverse";
  s["scene"] = o.scene;
  s["resolution"] = {res.x, res.y, res.z};
  s["voxelizer"] = vox.name;
  s.update(setup.build);
  s["threads"] = threads;
  s["seed"] = o.seed;
  s["gl_renderer"] = setup.gl ? setup.gl->renderer() : "none";
  s["cpu_threads_available"] = std::thread::hardware_concurrency();
  s["git_revision"] = gitRevision();
  s["lengths"] = nlohmann::json::array();
  for (float len : lengths) s["lengths"].push_back(benchRayLength(setup, o, tracers, len, threads));
  if (lengths.size() == 1) {  // one length: its fields at the top, as before the sweep
    for (auto& [k, v] : s["lengths"][0].items()) s[k] = v;
    s["max_dist"] = o.maxDist;
  } else {
    s["crossover_max_dist"] = crossover(s["lengths"]);
  }
  return s;
}

void printTraverseBench(const nlohmann::json& s) { printTraverse(s); }

}  // namespace vgi
