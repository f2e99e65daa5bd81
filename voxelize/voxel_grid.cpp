#include "voxelize/voxel_grid.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "core/error.h"
#include "core/hash.h"
#include "core/image.h"

namespace vgi {

shared::GridParams GridBox::params() const {
  shared::GridParams p;
  p.origin = glm::vec4(origin, 0.0f);
  p.axisX = glm::vec4(axes[0], float(resolution.x) / extent.x);
  p.axisY = glm::vec4(axes[1], float(resolution.y) / extent.y);
  p.axisZ = glm::vec4(axes[2], float(resolution.z) / extent.z);
  p.resolution = glm::uvec4(resolution, resolution.z / 128u);
  return p;
}

glm::uvec3 parseResolution(const std::string& text, const std::string& option) {
  long v[3] = {-1, -1, -1};
  auto parse = [](const std::string& s) {
    char* end = nullptr;
    long x = std::strtol(s.c_str(), &end, 10);
    return (s.empty() || *end) ? -1L : x;
  };
  size_t a = text.find('x');
  if (a == std::string::npos) {
    v[0] = v[1] = v[2] = parse(text);
  } else {
    size_t b = text.find('x', a + 1);
    if (b != std::string::npos) {
      v[0] = parse(text.substr(0, a));
      v[1] = parse(text.substr(a + 1, b - a - 1));
      v[2] = parse(text.substr(b + 1));
    }
  }
  if (v[0] < 1 || v[1] < 1 || v[2] < 1)
    fail(option, " '", text, "': expected N or WxHxD (e.g. 256 or 256x128x512)");
  if (v[0] > 8192 || v[1] > 8192) fail(option, " '", text, "': W and H must be at most 8192");
  if (v[2] % 128 != 0 || v[2] > 1024)
    fail(option, " '", text, "': the depth D = ", v[2], " must be 128, 256, 512 or 1024 (128-bit slabs)");
  return glm::uvec3(unsigned(v[0]), unsigned(v[1]), unsigned(v[2]));
}

GridBox fitGridBox(const Scene& scene, glm::uvec3 resolution, float time) {
  return fitGridBox(scene.bounds(time), resolution);
}

GridBox cubicCellBox(const GridBox& box) {
  const glm::vec3 v = box.voxelSize();
  const float side = std::max({v.x, v.y, v.z});
  GridBox g = box;
  g.extent = glm::vec3(box.resolution) * side;
  g.origin = box.origin + box.axes * (0.5f * (box.extent - g.extent));
  return g;
}

CellRange boundsCells(const GridBox& box, const Bounds& b, int below, int above) {
  if (b.empty()) return {};
  const glm::vec3 v = box.voxelSize(), n(box.resolution);
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (int c = 0; c < 8; ++c) {
    const glm::vec3 p((c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y, (c & 4) ? b.hi.z : b.lo.z);
    const glm::vec3 q = glm::transpose(box.axes) * (p - box.origin) / v;
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
  }
  // Clamped before the conversion (bounds far outside the grid fit no int).
  const glm::vec3 m(float(std::max(below, above)) + 1.0f);
  const glm::ivec3 a = glm::ivec3(glm::floor(glm::clamp(lo, -m, n + m))) - below,
                   z = glm::ivec3(glm::floor(glm::clamp(hi, -m, n + m))) + above;
  const glm::ivec3 res(box.resolution);
  const glm::ivec3 l = glm::clamp(a, glm::ivec3(0), res), h = glm::clamp(z, glm::ivec3(0), res);
  return {glm::uvec3(l), glm::uvec3(glm::max(h, l))};
}

GridBox fitGridBox(Bounds b, glm::uvec3 resolution) {
  if (b.empty()) fail("cannot fit a voxel grid: the scene is empty");
  GridBox g;
  g.resolution = resolution;
  glm::vec3 ext = b.hi - b.lo;
  float largest = std::max({ext.x, ext.y, ext.z, 1e-30f});
  glm::vec3 lo = b.lo;
  for (int i = 0; i < 3; ++i)
    if (ext[i] < 1e-4f * largest) {
      // Planar scene: a slab as thick as the cells of the largest axis are
      // long (cubic-ish cells, so texel-based voxelizers get a usable texel
      // size), with the plane through the centre of its middle cell (not on a
      // cell boundary, which would set two layers).
      int li = ext.x == largest ? 0 : (ext.y == largest ? 1 : 2);
      float w = largest * float(resolution[i]) / float(resolution[li]);
      float mid = lo[i] + 0.5f * ext[i];
      lo[i] = mid - w * (std::floor(float(resolution[i]) / 2.0f) + 0.5f) / float(resolution[i]);
      ext[i] = w;
    }
  // Pad by 1e-5 of the size on every side: surfaces lying on the bounds (the
  // walls of a box) then map strictly inside the grid whatever the rounding,
  // instead of landing a hair outside for one voxelizer and inside for another.
  const float pad = 1e-5f * std::max({ext.x, ext.y, ext.z});
  g.origin = lo - glm::vec3(pad);
  g.extent = ext + glm::vec3(2.0f * pad);
  return g;
}

void checkGridMemory(glm::uvec3 r, int grids) {
  const double bytes = double(r.x) * r.y * r.z / 8.0 * grids;
  const double phys = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  if (bytes > 0.5 * phys)
    fail("a ", r.x, "x", r.y, "x", r.z, " binary grid needs ", bytes / (1 << 20), " MiB; this machine has ",
         phys / (1 << 20), " MiB of memory (at most half of it is used for grids)");
}

BinaryGrid::BinaryGrid(const GridBox& box) : box_(box) {
  VGI_CHECK(box.resolution.z % 128u == 0 && box.resolution.x > 0 && box.resolution.y > 0);
  checkGridMemory(box.resolution);
  words_.assign(size_t(box.resolution.x) * box.resolution.y * (box.resolution.z / 32u), 0u);
}

void BinaryGrid::set(uint32_t x, uint32_t y, uint32_t z) {
  words_[wordIndex(x, y, shared::depthWord(z))] |= shared::depthBit(z);
}

void BinaryGrid::setAtomic(uint32_t x, uint32_t y, uint32_t z) {
  __atomic_fetch_or(&words_[wordIndex(x, y, shared::depthWord(z))], shared::depthBit(z), __ATOMIC_RELAXED);
}

bool BinaryGrid::test(uint32_t x, uint32_t y, uint32_t z) const {
  return (words_[wordIndex(x, y, shared::depthWord(z))] & shared::depthBit(z)) != 0u;
}

uint64_t BinaryGrid::count() const {
  uint64_t n = 0;
  for (uint32_t w : words_) n += uint64_t(__builtin_popcount(w));
  return n;
}

uint64_t BinaryGrid::digest() const { return fnv1a(words_.data(), words_.size() * sizeof(uint32_t)); }

uint32_t BinaryGrid::columnCount(uint32_t x, uint32_t y) const {
  uint32_t n = 0;
  for (uint32_t w = 0; w < wordsPerColumn(); ++w)
    n += uint32_t(__builtin_popcount(words_[wordIndex(x, y, w)]));
  return n;
}

void writeGridPicture(const BinaryGrid& grid, const std::string& path) {
  const glm::uvec3 r = grid.box().resolution;
  uint32_t maxCount = 1;
  for (uint32_t y = 0; y < r.y; ++y)
    for (uint32_t x = 0; x < r.x; ++x) maxCount = std::max(maxCount, grid.columnCount(x, y));
  Image img(int(2 * r.x + 2), int(r.y));
  for (uint32_t y = 0; y < r.y; ++y)
    for (uint32_t x = 0; x < r.x; ++x) {
      const int row = int(r.y - 1 - y);  // +y up in the picture
      float c = float(grid.columnCount(x, y)) / float(maxCount);
      img.at(int(x), row) = glm::vec3(c);
      for (uint32_t w = 0; w < grid.wordsPerColumn(); ++w) {
        uint32_t bits = grid.words()[grid.wordIndex(x, y, w)];
        if (!bits) continue;
        float d = float(w * 32u + uint32_t(__builtin_ctz(bits)) + 1u) / float(r.z);  // first set cell
        img.at(int(r.x + 2 + x), row) = glm::vec3(1.0f - d, 0.3f + 0.4f * d, d);
        break;
      }
    }
  for (uint32_t y = 0; y < r.y; ++y)
    img.at(int(r.x), int(y)) = img.at(int(r.x) + 1, int(y)) = glm::vec3(1, 1, 0);
  writeImage(img, path);
}

}  // namespace vgi
