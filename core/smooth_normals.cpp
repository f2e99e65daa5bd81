#include "core/smooth_normals.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/error.h"

namespace vgi {

namespace {

// Four 32-bit words (a group id and a vector's bits) hashed as one key.
struct Key4 {
  uint32_t w[4];
  bool operator==(const Key4& o) const { return std::memcmp(w, o.w, sizeof(w)) == 0; }
};
uint64_t mix64(uint64_t z) {  // splitmix64's finaliser
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// Key4 -> dense ids 0, 1, 2, … in order of first insertion: open addressing with linear probing in a
// power-of-two table kept at most half full (std::unordered_map's node per entry and division per
// probe cost more than the rest of the loader together on a 10^6-triangle mesh).
class IdMap {
 public:
  explicit IdMap(size_t expected) { resize(std::max<size_t>(16, expected * 2)); }
  size_t size() const { return keys_.size(); }
  // The key's id, inserting it (as size() - 1) if new; `inserted` says which.
  uint32_t insert(const Key4& k, bool& inserted) {
    if ((keys_.size() + 1) * 2 > slots_.size()) resize(slots_.size() * 2);
    size_t i = slot(k);
    inserted = slots_[i] == kEmpty;
    if (inserted) {
      slots_[i] = uint32_t(keys_.size());
      keys_.push_back(k);
    }
    return slots_[i];
  }
  // The key's id, or kEmpty.
  uint32_t find(const Key4& k) const { return slots_[slot(k)]; }
  static constexpr uint32_t kEmpty = 0xffffffffu;

 private:
  size_t slot(const Key4& k) const {
    const size_t mask = slots_.size() - 1;
    size_t i =
        size_t(mix64(mix64(uint64_t(k.w[0]) << 32 | k.w[1]) ^ (uint64_t(k.w[2]) << 32 | k.w[3]))) & mask;
    while (slots_[i] != kEmpty && !(keys_[slots_[i]] == k)) i = (i + 1) & mask;
    return i;
  }
  void resize(size_t n) {
    size_t cap = 16;
    while (cap < n) cap *= 2;
    slots_.assign(cap, kEmpty);
    for (uint32_t id = 0; id < keys_.size(); ++id) slots_[slot(keys_[id])] = id;
  }
  std::vector<Key4> keys_;
  std::vector<uint32_t> slots_;
};

uint32_t bits(float f) {
  f += 0.0f;  // -0 and +0 are one position
  uint32_t u;
  std::memcpy(&u, &f, sizeof(u));
  return u;
}

Key4 key(uint32_t tag, glm::vec3 v) { return {{tag, bits(v.x), bits(v.y), bits(v.z)}}; }

glm::vec3 unitFaceNormal(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  glm::vec3 n = glm::cross(b - a, c - a);
  float len = glm::length(n);
  return len > 0.0f && std::isfinite(len) ? n / len : glm::vec3(0.0f);
}

// Items grouped by an id in [0, groups): group g's items are members[start[g] .. start[g + 1]), in
// order of their index (a counting sort).
struct Groups {
  std::vector<uint32_t> start, members;
  Groups(const std::vector<uint32_t>& groupOf, size_t groups)
      : start(groups + 1, 0), members(groupOf.size()) {
    for (uint32_t g : groupOf) ++start[g + 1];
    for (size_t g = 0; g < groups; ++g) start[g + 1] += start[g];
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (uint32_t i = 0; i < groupOf.size(); ++i) members[fill[groupOf[i]]++] = i;
  }
};

}  // namespace

SmoothNormals smoothCornerNormals(const std::vector<glm::vec3>& positions,
                                  const std::vector<glm::uvec3>& triangles, float maxAngleDegrees,
                                  int maxDistinctNormals) {
  const float cosLimit = std::cos(glm::radians(maxAngleDegrees));
  // Corners -> distinct positions (exact bits); (position, face normal) -> clusters.
  IdMap positionIds(positions.size()), clusterIds(positions.size());
  std::vector<glm::vec3> unique;
  std::vector<glm::vec3> clusterNormal;
  std::vector<float> clusterCount;
  std::vector<uint32_t> clusterPosition, cornerCluster(triangles.size() * 3);
  std::vector<uint32_t> positionOfVertex(positions.size(), IdMap::kEmpty);
  for (size_t t = 0; t < triangles.size(); ++t) {
    const glm::uvec3& tri = triangles[t];
    const glm::vec3 n = unitFaceNormal(positions[tri[0]], positions[tri[1]], positions[tri[2]]);
    for (int k = 0; k < 3; ++k) {
      bool added;
      uint32_t& p = positionOfVertex[tri[k]];  // looked up once per vertex, not per corner
      if (p == IdMap::kEmpty) {
        p = positionIds.insert(key(0, positions[tri[k]]), added);
        if (added) unique.push_back(positions[tri[k]]);
      }
      const uint32_t c = clusterIds.insert(key(p, n), added);
      if (added) {
        clusterNormal.push_back(n);
        clusterCount.push_back(0.0f);
        clusterPosition.push_back(p);
      }
      clusterCount[c] += 1.0f;
      cornerCluster[t * 3 + k] = c;
    }
  }
  const Groups clustersAt(clusterPosition, unique.size());

  // Positions closer than assimp's epsilon (1e-4 of the mesh's diagonal) are one position. A grid of
  // cells twice that size, indexed from the bounds' corner: a position's neighbours lie in its cell or,
  // on each axis, in the adjacent cell on the side of the half it lies in (8 cells).
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const glm::vec3& p : unique) lo = glm::min(lo, glm::dvec3(p)), hi = glm::max(hi, glm::dvec3(p));
  const double eps = unique.empty() ? 0.0 : glm::length(hi - lo) * 1e-4;
  const float eps2 = float(eps * eps);
  auto gridOf = [&](glm::vec3 p) { return eps > 0 ? (glm::dvec3(p) - lo) / (2.0 * eps) : glm::dvec3(0.0); };
  auto cellOf = [&](glm::vec3 p) { return glm::ivec3(glm::floor(gridOf(p))); };
  IdMap cellIds(unique.size());
  std::vector<uint32_t> cellOfPosition(unique.size());
  for (size_t u = 0; u < unique.size(); ++u) {
    const glm::ivec3 c = cellOf(unique[u]);
    bool added;
    cellOfPosition[u] = cellIds.insert(Key4{{0, uint32_t(c.x), uint32_t(c.y), uint32_t(c.z)}}, added);
  }
  const Groups positionsIn(cellOfPosition, cellIds.size());

  SmoothNormals out;
  std::vector<glm::vec3> smooth(clusterNormal.size());
  std::vector<uint32_t> near;  // the clusters at positions within epsilon of this one
  for (uint32_t u = 0; u < unique.size(); ++u) {
    near.clear();
    const glm::dvec3 q = gridOf(unique[u]);
    const glm::ivec3 c = glm::ivec3(glm::floor(q));
    const glm::ivec3 side = glm::ivec3(glm::step(0.5, q - glm::floor(q))) * 2 - 1;
    for (int d = 0; d < 8 && int(near.size()) <= maxDistinctNormals; ++d) {
      const glm::ivec3 n = c + side * glm::ivec3(d & 1, d >> 1 & 1, d >> 2);
      const uint32_t cell = cellIds.find(Key4{{0, uint32_t(n.x), uint32_t(n.y), uint32_t(n.z)}});
      if (cell == IdMap::kEmpty) continue;
      for (uint32_t i = positionsIn.start[cell]; i < positionsIn.start[cell + 1]; ++i) {
        const uint32_t v = positionsIn.members[i];
        const glm::vec3 dv = unique[v] - unique[u];
        if (v != u && !(glm::dot(dv, dv) < eps2)) continue;
        for (uint32_t j = clustersAt.start[v]; j < clustersAt.start[v + 1]; ++j)
          near.push_back(clustersAt.members[j]);
        if (int(near.size()) > maxDistinctNormals) break;
      }
    }
    const bool flat = int(near.size()) > maxDistinctNormals;
    out.flatPositions += flat;
    for (uint32_t i = clustersAt.start[u]; i < clustersAt.start[u + 1]; ++i) {
      const uint32_t own = clustersAt.members[i];
      glm::vec3 sum = flat ? clusterNormal[own] : glm::vec3(0.0f);
      if (!flat)
        for (uint32_t j : near)
          if (glm::dot(clusterNormal[own], clusterNormal[j]) >= cosLimit)
            sum += clusterCount[j] * clusterNormal[j];
      const float len = glm::length(sum);
      smooth[own] = len > 0.0f ? sum / len : glm::vec3(0.0f);
    }
  }
  out.normals.resize(cornerCluster.size());
  for (size_t i = 0; i < cornerCluster.size(); ++i) out.normals[i] = smooth[cornerCluster[i]];
  return out;
}

WeldedNormals weldCornerNormals(const std::vector<glm::uvec3>& triangles,
                                const std::vector<glm::vec3>& cornerNormals) {
  if (cornerNormals.size() != triangles.size() * 3)
    fail("internal: ", cornerNormals.size(), " corner normals for ", triangles.size(), " triangles");
  WeldedNormals w;
  IdMap ids(triangles.size() * 3 / 2);
  w.triangles.resize(triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 n = cornerNormals[t * 3 + k];
      bool added;
      w.triangles[t][k] = ids.insert(key(triangles[t][k], n), added);
      if (added) {
        w.source.push_back(triangles[t][k]);
        w.normals.push_back(n);
      }
    }
  return w;
}

}  // namespace vgi
