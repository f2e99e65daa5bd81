// The exact reference voxelizer: it defines truth for every other voxelizer.
// A cell is set iff its closed box overlaps a triangle (separating axis test,
// Akenine-Möller, JGT 2001), evaluated in grid coordinates (cells are unit
// cubes; the affine map world → grid preserves overlap) and double precision.
// Consequence of closed boxes: a plane lying exactly on an internal cell
// boundary sets the cells on both sides.
//
// Per triangle, only columns inside its bounding box are visited, and per
// column only the depth range of the triangle clipped to that column (a
// conservative prefilter, widened by 1e-9; the SAT decides).
#include "voxelize/exact_voxelizer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

namespace vgi {

bool triangleBoxOverlap(glm::dvec3 center, glm::dvec3 h, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  a -= center;
  b -= center;
  c -= center;
  const glm::dvec3 e[3] = {b - a, c - b, a - c};
  // 9 axes: unit axis i × edge j.
  for (int i = 0; i < 3; ++i)
    for (const glm::dvec3& ej : e) {
      glm::dvec3 u(0.0);
      u[i] = 1.0;
      glm::dvec3 axis = glm::cross(u, ej);
      double pa = glm::dot(axis, a), pb = glm::dot(axis, b), pc = glm::dot(axis, c);
      double r = h.x * std::abs(axis.x) + h.y * std::abs(axis.y) + h.z * std::abs(axis.z);
      if (std::min({pa, pb, pc}) > r || std::max({pa, pb, pc}) < -r) return false;
    }
  // 3 box normals: the triangle's bounding box against the box.
  for (int i = 0; i < 3; ++i)
    if (std::min({a[i], b[i], c[i]}) > h[i] || std::max({a[i], b[i], c[i]}) < -h[i]) return false;
  // The triangle's plane against the box.
  glm::dvec3 n = glm::cross(e[0], e[1]);
  double d = glm::dot(n, a);
  double r = h.x * std::abs(n.x) + h.y * std::abs(n.y) + h.z * std::abs(n.z);
  return std::abs(d) <= r;
}

namespace {

struct Vtx {
  double x, y, z;
};

// Sutherland–Hodgman clip of a convex polygon against coord[axis] ≥ v (sign +1)
// or ≤ v (sign −1); carries z along.
int clip(const Vtx* in, int n, Vtx* out, int axis, double v, double sign) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const Vtx& p = in[i];
    const Vtx& q = in[(i + 1) % n];
    double dp = sign * ((axis == 0 ? p.x : p.y) - v), dq = sign * ((axis == 0 ? q.x : q.y) - v);
    if (dp >= 0) out[m++] = p;
    if ((dp >= 0) != (dq >= 0)) {
      double t = dp / (dp - dq);
      out[m++] = {p.x + t * (q.x - p.x), p.y + t * (q.y - p.y), p.z + t * (q.z - p.z)};
    }
  }
  return m;
}

}  // namespace

BinaryGrid voxelizeExact(const Scene& scene, const GridBox& box, float time, int threads, double shrink) {
  BinaryGrid grid(box);
  FlatScene flat = flatten(scene, time);
  const glm::dvec3 res(box.resolution);
  const glm::dmat3 axes(box.axes);
  const glm::dvec3 scale = res / glm::dvec3(box.extent);
  auto toGrid = [&](glm::vec3 p) {
    glm::dvec3 d = glm::dvec3(p) - glm::dvec3(box.origin);
    return glm::dvec3(glm::dot(d, axes[0]), glm::dot(d, axes[1]), glm::dot(d, axes[2])) * scale;
  };
  const glm::dvec3 half(0.5 - shrink);
  const double eps = 1e-9;
  // Cells whose closed box [i, i+1] can touch the interval [lo, hi].
  auto cellRange = [](double lo, double hi, unsigned n, int& first, int& last) {
    first = std::max(0, int(std::ceil(lo - 1e-9)) - 1);
    last = std::min(int(n) - 1, int(std::floor(hi + 1e-9)));
    return first <= last;
  };
  const size_t tris = flat.triangleCount();
  std::atomic<size_t> next{0};
  auto work = [&] {
    for (size_t t; (t = next.fetch_add(256)) < tris;)
      for (size_t i = t; i < std::min(tris, t + 256); ++i) {
        glm::dvec3 v[3] = {toGrid(flat.positions[3 * i]), toGrid(flat.positions[3 * i + 1]),
                           toGrid(flat.positions[3 * i + 2])};
        glm::dvec3 lo = glm::min(v[0], glm::min(v[1], v[2])), hi = glm::max(v[0], glm::max(v[1], v[2]));
        int x0, x1, y0, y1, z0, z1;
        if (!cellRange(lo.x, hi.x, box.resolution.x, x0, x1) ||
            !cellRange(lo.y, hi.y, box.resolution.y, y0, y1) ||
            !cellRange(lo.z, hi.z, box.resolution.z, z0, z1))
          continue;
        for (int y = y0; y <= y1; ++y)
          for (int x = x0; x <= x1; ++x) {
            Vtx a[9] = {{v[0].x, v[0].y, v[0].z}, {v[1].x, v[1].y, v[1].z}, {v[2].x, v[2].y, v[2].z}}, b[9];
            int n = clip(a, 3, b, 0, x - eps, 1.0);
            n = clip(b, n, a, 0, x + 1 + eps, -1.0);
            n = clip(a, n, b, 1, y - eps, 1.0);
            n = clip(b, n, a, 1, y + 1 + eps, -1.0);
            if (n == 0) continue;
            double zmin = a[0].z, zmax = a[0].z;
            for (int k = 1; k < n; ++k) {
              zmin = std::min(zmin, a[k].z);
              zmax = std::max(zmax, a[k].z);
            }
            int za, zb;
            if (!cellRange(zmin - eps, zmax + eps, box.resolution.z, za, zb)) continue;
            for (int z = std::max(za, z0); z <= std::min(zb, z1); ++z)
              if (triangleBoxOverlap(glm::dvec3(x, y, z) + 0.5, half, v[0], v[1], v[2]))
                grid.setAtomic(uint32_t(x), uint32_t(y), uint32_t(z));
          }
      }
  };
  int n = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
  std::vector<std::thread> pool;
  for (int i = 0; i < n; ++i) pool.emplace_back(work);
  for (auto& th : pool) th.join();
  return grid;
}

}  // namespace vgi
