#include "voxelize/atlas.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/hash.h"
#include "voxelize/atlas_packing.h"
#include "voxelize/chart_parametrization.h"
#include "voxelize/setup_cache.h"

namespace vgi {

nlohmann::json MeshAtlas::toJson() const {
  return {{"resolution", resolution},
          {"texel_world", texelWorld},
          {"charts", charts},
          {"lscm_charts", lscmCharts},
          {"faces_split_off", facesSplitOff},
          {"utilization", utilization},
          {"max_stretch", maxStretch},
          {"ms", ms},
          {"from_cache", fromCache}};
}

float autoTexelWorld(glm::vec3 voxelSize, float texelsPerVoxel) {
  return std::min({voxelSize.x, voxelSize.y, voxelSize.z}) / texelsPerVoxel;
}

namespace {

constexpr uint32_t kCacheVersion = 2;  // 2: the set-up cache's file format (voxelize/setup_cache.h)

uint64_t contentHash(const std::vector<glm::vec3>& P, const std::vector<glm::uvec3>& T,
                     const AtlasOptions& o) {
  uint64_t h = fnv1a(&kCacheVersion, sizeof kCacheVersion);
  h = fnv1a(P.data(), P.size() * sizeof(glm::vec3), h);
  h = fnv1a(T.data(), T.size() * sizeof(glm::uvec3), h);
  float params[5] = {o.texelWorld, float(o.resolution), float(o.gutter), o.segmentation.maxNormalDeviationDeg,
                     o.segmentation.planarDeviationDeg};
  h = fnv1a(params, sizeof params, h);
  uint64_t mf = o.segmentation.maxFaces;
  return fnv1a(&mf, sizeof mf, h);
}

// The atlas's entry in the set-up cache: these fields, then the UVs.
struct CacheMeta {
  int32_t resolution, charts, lscmCharts, pad;
  int64_t facesSplitOff, uvCount;
  float texelWorld, maxStretch;
  double utilization;
};

bool readCache(const std::string& dir, uint64_t key, size_t triangles, MeshAtlas& a) {
  std::vector<uint8_t> payload;
  if (!readSetupCache(dir, "atlas", key, payload) || payload.size() < sizeof(CacheMeta)) return false;
  CacheMeta m;
  std::memcpy(&m, payload.data(), sizeof m);
  if (m.uvCount != int64_t(3 * triangles) ||
      payload.size() != sizeof m + size_t(m.uvCount) * sizeof(glm::vec2))
    return false;
  a.uv.resize(size_t(m.uvCount));
  std::memcpy(static_cast<void*>(a.uv.data()), payload.data() + sizeof m, a.uv.size() * sizeof(glm::vec2));
  a.resolution = m.resolution;
  a.charts = m.charts;
  a.lscmCharts = m.lscmCharts;
  a.facesSplitOff = m.facesSplitOff;
  a.texelWorld = m.texelWorld;
  a.maxStretch = m.maxStretch;
  a.utilization = m.utilization;
  return true;
}

void writeCache(const std::string& dir, uint64_t key, const MeshAtlas& a) {
  const CacheMeta m{a.resolution, a.charts,     a.lscmCharts, 0, a.facesSplitOff, int64_t(a.uv.size()),
                    a.texelWorld, a.maxStretch, a.utilization};
  std::vector<uint8_t> payload(sizeof m + a.uv.size() * sizeof(glm::vec2));
  std::memcpy(payload.data(), &m, sizeof m);
  std::memcpy(payload.data() + sizeof m, a.uv.data(), a.uv.size() * sizeof(glm::vec2));
  writeSetupCache(dir, "atlas", key, payload.data(), payload.size());  // unwritable: only costs time
}

// Rotates a chart so its principal UV axis is horizontal (smaller bounding box).
void alignChart(FlatChart& c) {
  glm::vec2 mean(0.0f);
  for (auto& p : c.uv) mean += p;
  mean /= float(c.uv.size());
  float sxx = 0, sxy = 0, syy = 0;
  for (auto& p : c.uv) {
    glm::vec2 d = p - mean;
    sxx += d.x * d.x, sxy += d.x * d.y, syy += d.y * d.y;
  }
  float angle = 0.5f * std::atan2(2 * sxy, sxx - syy);
  float cs = std::cos(-angle), sn = std::sin(-angle);
  for (auto& p : c.uv) {
    glm::vec2 d = p - mean;
    p = {cs * d.x - sn * d.y, sn * d.x + cs * d.y};
  }
}

}  // namespace

MeshAtlas buildAtlas(const std::vector<glm::vec3>& P, const std::vector<glm::uvec3>& T,
                     const AtlasOptions& opt, int maxResolution) {
  auto t0 = std::chrono::steady_clock::now();
  if (opt.texelWorld <= 0 && opt.resolution <= 0) fail("atlas: give a texel size or a resolution");
  if (opt.resolution > maxResolution)
    fail("atlas resolution ", opt.resolution, " exceeds the largest texture (", maxResolution, ")");
  MeshAtlas atlas;
  const uint64_t key = opt.cacheDir.empty() ? 0 : contentHash(P, T, opt);
  if (!opt.cacheDir.empty()) {
    if (readCache(opt.cacheDir, key, T.size(), atlas)) {
      atlas.fromCache = true;
      atlas.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      return atlas;
    }
  }

  Segmentation seg = segmentCharts(P, T, opt.segmentation);
  std::vector<FlatChart> charts;
  for (const Chart& c : seg.charts)
    for (FlatChart& f : parametrizeChart(P, T, c)) charts.push_back(std::move(f));
  double chartArea = 0;  // world units²
  for (FlatChart& c : charts) {
    alignChart(c);
    atlas.lscmCharts += c.lscm;
    atlas.maxStretch = std::max(atlas.maxStretch, c.maxStretch);
    for (size_t i = 0; i < c.faces.size(); ++i) {
      glm::vec2 a = c.uv[3 * i + 1] - c.uv[3 * i], b = c.uv[3 * i + 2] - c.uv[3 * i];
      chartArea += 0.5 * std::abs(double(a.x) * b.y - double(a.y) * b.x);
    }
  }

  // Pack at a texel size; with a manual resolution, search the texel size that fits.
  auto pack = [&](float texel, std::vector<glm::vec2>& lows, ShelfPacking& sp) {
    std::vector<glm::ivec2> sizes;
    lows.clear();
    for (const FlatChart& c : charts) {
      glm::vec2 lo(1e30f), hi(-1e30f);
      for (auto& p : c.uv) lo = glm::min(lo, p / texel), hi = glm::max(hi, p / texel);
      lows.push_back(lo);
      sizes.push_back(glm::ivec2(glm::ceil(hi - lo)) + glm::ivec2(1 + 2 * opt.gutter));
    }
    sp = packShelves(sizes);
    return std::max(sp.width, sp.height);
  };
  float texel = opt.texelWorld;
  std::vector<glm::vec2> lows;
  ShelfPacking sp;
  int side;
  if (opt.resolution > 0) {
    texel = float(std::sqrt(chartArea / (0.6 * double(opt.resolution) * opt.resolution)));
    if (!(texel > 0)) texel = 1;
    for (int it = 0; (side = pack(texel, lows, sp)) > opt.resolution; ++it) {
      if (it > 60) fail("atlas: cannot pack ", charts.size(), " charts into ", opt.resolution, "² texels");
      texel *= 1.0f + std::min(0.5f, 1.02f * float(side) / float(opt.resolution) - 1.0f + 0.01f);
    }
    side = opt.resolution;
  } else {
    double texels = chartArea / (double(texel) * texel);
    if (texels > double(maxResolution) * maxResolution)
      fail("atlas: ", charts.size(), " charts at texel size ", texel, " need about ", std::sqrt(texels),
           "² texels, more than the largest texture (", maxResolution,
           "²); use a coarser voxel grid or a manual atlas resolution");
    side = pack(texel, lows, sp);
    if (side > maxResolution)
      fail("atlas: packing needs ", side, "² texels, more than the largest texture (", maxResolution, "²)");
  }

  atlas.resolution = side;
  atlas.texelWorld = texel;
  atlas.charts = int(charts.size());
  atlas.facesSplitOff = seg.facesSplitOff;
  atlas.utilization = chartArea / (double(texel) * texel) / (double(side) * side);
  atlas.uv.assign(3 * T.size(), glm::vec2(0.0f));
  for (size_t ci = 0; ci < charts.size(); ++ci) {
    const FlatChart& c = charts[ci];
    glm::vec2 shift = glm::vec2(sp.offsets[ci]) + glm::vec2(float(opt.gutter) + 0.5f) - lows[ci];
    for (size_t i = 0; i < c.faces.size(); ++i)
      for (int k = 0; k < 3; ++k)
        atlas.uv[3 * c.faces[i] + size_t(k)] = (c.uv[3 * i + size_t(k)] / texel + shift) / float(side);
  }
  if (!opt.cacheDir.empty()) writeCache(opt.cacheDir, key, atlas);
  atlas.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return atlas;
}

}  // namespace vgi
