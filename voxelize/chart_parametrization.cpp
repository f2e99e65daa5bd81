// Chart parametrization: planar projection, or Least Squares Conformal Maps
// (Lévy, Petitjean, Ray, Maillot, SIGGRAPH 2002, §3–4): per triangle with local
// 2D coordinates q_j, area A and W_j = q_{j+2} − q_{j+1} as complex numbers, the
// conformality condition Σ_j W_j U_j = 0 (U_j = u_j + i v_j), weighted by
// 1/sqrt(2A), is solved in the least-squares sense with two vertices pinned,
// through the normal equations and Eigen's sparse LDLᵀ.
#include "voxelize/chart_parametrization.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <unordered_map>

#include "shaders/shared/sampling.glsl"

namespace vgi {

namespace {

float cross2(glm::vec2 a, glm::vec2 b) { return a.x * b.y - a.y * b.x; }

void planarProject(const std::vector<glm::vec3>& P, const std::vector<glm::uvec3>& T, glm::vec3 n,
                   FlatChart& out) {
  shared::Basis f = shared::makeBasis(glm::normalize(n));
  out.uv.clear();
  for (uint32_t t : out.faces)
    for (int k = 0; k < 3; ++k) out.uv.push_back({glm::dot(P[T[t][k]], f.t), glm::dot(P[T[t][k]], f.b)});
}

bool lscm(const std::vector<glm::vec3>& P, const std::vector<glm::uvec3>& T, FlatChart& out) {
  std::unordered_map<uint32_t, int> local;
  std::vector<uint32_t> verts;
  for (uint32_t t : out.faces)
    for (int k = 0; k < 3; ++k)
      if (local.emplace(T[t][k], int(verts.size())).second) verts.push_back(T[t][k]);
  const int n = int(verts.size());
  if (n < 3) return false;
  // Pins: the two vertices farthest apart along the chart's main extent.
  int pa = 0, pb = 0;
  {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (uint32_t v : verts) lo = glm::min(lo, P[v]), hi = glm::max(hi, P[v]);
    glm::vec3 ext = hi - lo;
    int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
    for (int i = 0; i < n; ++i) {
      if (P[verts[size_t(i)]][axis] < P[verts[size_t(pa)]][axis]) pa = i;
      if (P[verts[size_t(i)]][axis] > P[verts[size_t(pb)]][axis]) pb = i;
    }
    if (pa == pb) return false;
  }
  const double pinDist = glm::length(P[verts[size_t(pb)]] - P[verts[size_t(pa)]]);
  // Unknowns: u and v of every vertex but the two pins.
  std::vector<int> col(static_cast<size_t>(n), -1);
  int free = 0;
  for (int i = 0; i < n; ++i)
    if (i != pa && i != pb) col[size_t(i)] = free++;
  const double pinU[2] = {0.0, pinDist}, pinV[2] = {0.0, 0.0};
  std::vector<Eigen::Triplet<double>> trip;
  std::vector<double> rhs;
  int row = 0;
  for (uint32_t t : out.faces) {
    glm::dvec3 p0 = P[T[t][0]], p1 = P[T[t][1]], p2 = P[T[t][2]];
    glm::dvec3 c = glm::cross(p1 - p0, p2 - p0);
    double twoA = glm::length(c);
    if (!(twoA > 1e-30)) continue;
    glm::dvec3 x = glm::normalize(p1 - p0), y = glm::cross(c / twoA, x);
    glm::dvec2 q[3] = {{0, 0}, {glm::length(p1 - p0), 0}, {glm::dot(p2 - p0, x), glm::dot(p2 - p0, y)}};
    double w = 1.0 / std::sqrt(twoA);
    double re = 0, im = 0;
    for (int j = 0; j < 3; ++j) {
      glm::dvec2 W = (q[(j + 2) % 3] - q[(j + 1) % 3]) * w;  // a + ib
      int vi = local[T[t][j]];
      if (col[size_t(vi)] >= 0) {
        int cu = col[size_t(vi)], cv = free + col[size_t(vi)];
        trip.emplace_back(row, cu, W.x);  // re: a u − b v
        trip.emplace_back(row, cv, -W.y);
        trip.emplace_back(row + 1, cu, W.y);  // im: b u + a v
        trip.emplace_back(row + 1, cv, W.x);
      } else {
        int k = vi == pa ? 0 : 1;
        re -= W.x * pinU[k] - W.y * pinV[k];
        im -= W.y * pinU[k] + W.x * pinV[k];
      }
    }
    rhs.push_back(re);
    rhs.push_back(im);
    row += 2;
  }
  if (free == 0) {
    out.uv.clear();
    for (uint32_t t : out.faces)
      for (int k = 0; k < 3; ++k) {
        int vi = local[T[t][k]];
        out.uv.push_back({vi == pa ? 0.0f : float(pinDist), 0.0f});
      }
    return true;
  }
  Eigen::SparseMatrix<double> A(row, 2 * free);
  A.setFromTriplets(trip.begin(), trip.end());
  Eigen::Map<Eigen::VectorXd> b(rhs.data(), Eigen::Index(rhs.size()));
  Eigen::SparseMatrix<double> AtA = A.transpose() * A;
  Eigen::VectorXd Atb = A.transpose() * b;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(AtA);
  if (solver.info() != Eigen::Success) return false;
  Eigen::VectorXd x = solver.solve(Atb);
  if (solver.info() != Eigen::Success || !x.allFinite()) return false;
  std::vector<glm::dvec2> uv(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i)
    uv[size_t(i)] = col[size_t(i)] >= 0 ? glm::dvec2(x[col[size_t(i)]], x[free + col[size_t(i)]])
                                        : glm::dvec2(i == pa ? pinU[0] : pinU[1], 0.0);
  // Scale so that the UV area equals the surface area (uniform texel density).
  double area3 = 0, area2 = 0;
  for (uint32_t t : out.faces) {
    area3 += 0.5 * glm::length(
                       glm::cross(glm::dvec3(P[T[t][1]] - P[T[t][0]]), glm::dvec3(P[T[t][2]] - P[T[t][0]])));
    glm::dvec2 a = uv[size_t(local[T[t][0]])], bb = uv[size_t(local[T[t][1]])],
               cc = uv[size_t(local[T[t][2]])];
    area2 += 0.5 * std::abs((bb.x - a.x) * (cc.y - a.y) - (bb.y - a.y) * (cc.x - a.x));
  }
  if (!(area2 > 0)) return false;
  const double s = std::sqrt(area3 / area2);
  out.uv.clear();
  for (uint32_t t : out.faces)
    for (int k = 0; k < 3; ++k) out.uv.push_back(glm::vec2(uv[size_t(local[T[t][k]])] * s));
  return true;
}

float stretchOf(const std::vector<glm::vec3>& P, const std::vector<glm::uvec3>& T, const FlatChart& c) {
  float worst = 0;
  for (size_t i = 0; i < c.faces.size(); ++i) {
    const glm::uvec3& t = T[c.faces[i]];
    glm::vec2 du1 = c.uv[3 * i + 1] - c.uv[3 * i], du2 = c.uv[3 * i + 2] - c.uv[3 * i];
    float det = cross2(du1, du2);
    if (std::abs(det) < 1e-30f) return 1e30f;
    glm::vec3 dp1 = P[t[1]] - P[t[0]], dp2 = P[t[2]] - P[t[0]];
    // J = [dp1 dp2] · [du1 du2]⁻¹; its largest singular value.
    glm::vec3 ju = (dp1 * du2.y - dp2 * du1.y) / det, jv = (dp2 * du1.x - dp1 * du2.x) / det;
    float a = glm::dot(ju, ju), b = glm::dot(ju, jv), d = glm::dot(jv, jv);
    float l = 0.5f * (a + d) + std::sqrt(std::max(0.0f, 0.25f * (a - d) * (a - d) + b * b));
    worst = std::max(worst, std::sqrt(l));
  }
  return worst;
}

// Edge-connected components of a face set. (Faces meeting only at a vertex
// would leave LSCM free to rotate one about the other: underdetermined.)
std::vector<std::vector<uint32_t>> components(const std::vector<glm::uvec3>& T,
                                              const std::vector<uint32_t>& faces) {
  std::vector<size_t> parent(faces.size());
  std::iota(parent.begin(), parent.end(), size_t(0));
  std::function<size_t(size_t)> find = [&](size_t i) {
    return parent[i] == i ? i : parent[i] = find(parent[i]);
  };
  std::map<std::pair<uint32_t, uint32_t>, size_t> edgeOwner;
  for (size_t i = 0; i < faces.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      uint32_t a = T[faces[i]][k], b = T[faces[i]][(k + 1) % 3];
      auto [it, fresh] = edgeOwner.emplace(std::make_pair(std::min(a, b), std::max(a, b)), i);
      if (!fresh) parent[find(i)] = find(it->second);
    }
  std::map<size_t, std::vector<uint32_t>> groups;
  for (size_t i = 0; i < faces.size(); ++i) groups[find(i)].push_back(faces[i]);
  std::vector<std::vector<uint32_t>> out;
  for (auto& [k, g] : groups) out.push_back(std::move(g));
  return out;
}

void parametrizeRecursive(const std::vector<glm::vec3>& P, const std::vector<glm::uvec3>& T,
                          std::vector<uint32_t> faces, glm::vec3 normal, bool planar,
                          std::vector<FlatChart>& out) {
  FlatChart c;
  c.faces = std::move(faces);
  bool ok;
  if (planar || c.faces.size() == 1) {
    planarProject(P, T,
                  c.faces.size() == 1 ? glm::cross(P[T[c.faces[0]][1]] - P[T[c.faces[0]][0]],
                                                   P[T[c.faces[0]][2]] - P[T[c.faces[0]][0]])
                                      : normal,
                  c);
    ok = true;
  } else {
    c.lscm = true;
    ok = lscm(P, T, c);
  }
  if (ok && (c.faces.size() == 1 || chartIsValid(T, c))) {
    c.maxStretch = stretchOf(P, T, c);
    out.push_back(std::move(c));
    return;
  }
  // Split in two (the faces are in region-growing order, so halves are compact) and retry each component.
  size_t half = c.faces.size() / 2;
  std::vector<uint32_t> a(c.faces.begin(), c.faces.begin() + long(half)),
      b(c.faces.begin() + long(half), c.faces.end());
  for (auto* part : {&a, &b})
    for (auto& comp : components(T, *part)) {
      glm::vec3 n(0.0f);
      for (uint32_t f : comp) n += glm::cross(P[T[f][1]] - P[T[f][0]], P[T[f][2]] - P[T[f][0]]);
      parametrizeRecursive(P, T, comp, glm::length(n) > 0 ? n : normal, false, out);
    }
}

}  // namespace

bool chartIsValid(const std::vector<glm::uvec3>& T, const FlatChart& c) {
  const size_t n = c.faces.size();
  glm::vec2 lo(1e30f), hi(-1e30f);
  for (auto& p : c.uv) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const float scale = std::max(hi.x - lo.x, hi.y - lo.y);
  if (!(scale > 0) || !std::isfinite(scale)) return false;
  for (size_t i = 0; i < n; ++i)
    if (!(cross2(c.uv[3 * i + 1] - c.uv[3 * i], c.uv[3 * i + 2] - c.uv[3 * i]) > 1e-12f * scale * scale))
      return false;
  if (n < 2) return true;
  // Bucket faces by bounding box into a grid of about n cells.
  const int g = std::max(1, int(std::sqrt(double(n))));
  auto cellOf = [&](float v, float l) {
    return std::min(g - 1, std::max(0, int((v - l) / scale * float(g))));
  };
  std::vector<std::vector<uint32_t>> buckets(size_t(g) * size_t(g));
  for (size_t i = 0; i < n; ++i) {
    glm::vec2 a = glm::min(c.uv[3 * i], glm::min(c.uv[3 * i + 1], c.uv[3 * i + 2]));
    glm::vec2 b = glm::max(c.uv[3 * i], glm::max(c.uv[3 * i + 1], c.uv[3 * i + 2]));
    for (int y = cellOf(a.y, lo.y); y <= cellOf(b.y, lo.y); ++y)
      for (int x = cellOf(a.x, lo.x); x <= cellOf(b.x, lo.x); ++x)
        buckets[size_t(y) * size_t(g) + size_t(x)].push_back(uint32_t(i));
  }
  const float eps = 1e-5f * scale;
  auto overlap = [&](size_t i, size_t j) {
    const glm::vec2* A = &c.uv[3 * i];
    const glm::vec2* B = &c.uv[3 * j];
    for (const glm::vec2* tri : {A, B})
      for (int e = 0; e < 3; ++e) {
        glm::vec2 d = tri[(e + 1) % 3] - tri[e];
        glm::vec2 axis(-d.y, d.x);
        float len = glm::length(axis);
        if (len == 0) continue;
        axis /= len;
        float a0 = 1e30f, a1 = -1e30f, b0 = 1e30f, b1 = -1e30f;
        for (int k = 0; k < 3; ++k) {
          float pa = glm::dot(A[k], axis), pb = glm::dot(B[k], axis);
          a0 = std::min(a0, pa), a1 = std::max(a1, pa), b0 = std::min(b0, pb), b1 = std::max(b1, pb);
        }
        if (std::min(a1, b1) - std::max(a0, b0) <= eps) return false;  // separated or only touching
      }
    return true;
  };
  for (auto& bucket : buckets)
    for (size_t x = 0; x < bucket.size(); ++x)
      for (size_t y = x + 1; y < bucket.size(); ++y) {
        const glm::uvec3 &fa = T[c.faces[bucket[x]]], &fb = T[c.faces[bucket[y]]];
        int shared = 0;
        for (int p = 0; p < 3; ++p)
          for (int q = 0; q < 3; ++q) shared += fa[p] == fb[q];
        if (shared >= 2) continue;  // edge neighbours touch along the edge
        if (overlap(bucket[x], bucket[y])) return false;
      }
  return true;
}

std::vector<FlatChart> parametrizeChart(const std::vector<glm::vec3>& P, const std::vector<glm::uvec3>& T,
                                        const Chart& chart) {
  std::vector<FlatChart> out;
  parametrizeRecursive(P, T, chart.faces, chart.normal, chart.planar, out);
  return out;
}

}  // namespace vgi
