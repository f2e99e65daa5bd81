#include "voxelize/mesh_simplify.h"

#include "voxelize/openmesh_build.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <Eigen/SVD>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModHausdorffT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "core/scene.h"

namespace vgi {

namespace {

// Corners with the same position become one vertex (a loader splits them at
// uv and normal seams, which would leave every seam a boundary).
void weld(const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& tris,
          std::vector<glm::vec3>& outPositions, std::vector<glm::uvec3>& outTris) {
  std::map<std::tuple<float, float, float>, uint32_t> index;
  std::vector<uint32_t> remap(positions.size());
  for (size_t i = 0; i < positions.size(); ++i) {
    const glm::vec3& p = positions[i];
    auto [it, fresh] = index.emplace(std::make_tuple(p.x, p.y, p.z), uint32_t(outPositions.size()));
    if (fresh) outPositions.push_back(p);
    remap[i] = it->second;
  }
  outTris.reserve(tris.size());
  for (const glm::uvec3& t : tris) outTris.emplace_back(remap[t.x], remap[t.y], remap[t.z]);
}

// Binary: a collapse is legal if every face it moves keeps its centroid and
// edge midpoints near the original surface (the other direction of the
// two-sided tolerance; ModHausdorff checks the removed points).
template <class MeshT>
class ModNearSurfaceT : public OpenMesh::Decimater::ModBaseT<MeshT> {
 public:
  DECIMATING_MODULE(ModNearSurfaceT, MeshT, NearSurface);
  explicit ModNearSurfaceT(MeshT& mesh) : Base(mesh, true) {}
  void setTest(const NearSurface* test) { test_ = test; }
  float collapse_priority(const CollapseInfo& ci) override {
    Mesh& m = Base::mesh();
    m.set_point(ci.v0, ci.p1);  // simulate the collapse
    bool ok = true;
    for (auto fh : m.vf_range(ci.v0)) {
      if (fh == ci.fl || fh == ci.fr) continue;
      glm::vec3 p[3];
      int k = 0;
      for (auto v : m.fv_range(fh)) {
        const auto& q = m.point(v);
        p[k++] = glm::vec3(q[0], q[1], q[2]);
      }
      const glm::vec3 c = glm::cross(p[1] - p[0], p[2] - p[0]);
      const float len = glm::length(c);
      if (!(len > 0.0f)) continue;  // a degenerate face covers nothing
      const glm::vec3 n = c / len;
      const glm::vec3 samples[4] = {(p[0] + p[1] + p[2]) / 3.0f, 0.5f * (p[0] + p[1]), 0.5f * (p[1] + p[2]),
                                    0.5f * (p[2] + p[0])};
      for (const glm::vec3& s : samples)
        if (!(*test_)(s, n)) {
          ok = false;
          break;
        }
      if (!ok) break;
    }
    m.set_point(ci.v0, ci.p0);
    return ok ? float(Base::LEGAL_COLLAPSE) : float(Base::ILLEGAL_COLLAPSE);
  }

 private:
  const NearSurface* test_ = nullptr;
};

// An upper bound on how much mesh `m`'s object-to-world transform stretches
// a length, at any time: the static transform's largest singular value times
// the keyframes' largest scale (linear in time between keyframes, so largest
// at one of them; rotations do not stretch).
float maxStretch(const Mesh& m) {
  Eigen::Matrix3f a;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a(r, c) = m.transform[c][r];
  float s = Eigen::JacobiSVD<Eigen::Matrix3f>(a).singularValues()(0);
  if (m.dynamic && !m.keyframes.empty()) {
    float k = 0.0f;
    for (const Keyframe& f : m.keyframes)
      k = std::max(k, glm::max(glm::max(std::abs(f.scale.x), std::abs(f.scale.y)), std::abs(f.scale.z)));
    s *= k;
  }
  return s;
}

// Quadric collapses down to `target` faces under the guards; whether any was made.
bool decimate(OMesh& mesh, size_t target, float tolerance, const NearSurface& nearOriginal) {
  using Decimater = OpenMesh::Decimater::DecimaterT<OMesh>;
  Decimater dec(mesh);
  OpenMesh::Decimater::ModQuadricT<OMesh>::Handle quadric;
  OpenMesh::Decimater::ModNormalFlippingT<OMesh>::Handle flipping;
  OpenMesh::Decimater::ModHausdorffT<OMesh>::Handle hausdorff;
  typename ModNearSurfaceT<OMesh>::Handle nearSurface;
  dec.add(quadric);
  dec.add(flipping);
  dec.add(hausdorff);
  if (nearOriginal) {
    dec.add(nearSurface);
    dec.module(nearSurface).setTest(&nearOriginal);
  }
  dec.module(quadric).unset_max_err();
  dec.module(hausdorff).set_tolerance(tolerance);
  dec.initialize();
  return dec.decimate_to_faces(0, target) > 0;
}

}  // namespace

SimplifiedMesh simplifyMesh(const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& tris,
                            size_t target, float tolerance, const NearSurface& nearOriginal) {
  SimplifiedMesh out;
  std::vector<glm::vec3> welded;
  std::vector<glm::uvec3> weldedTris;
  weld(positions, tris, welded, weldedTris);
  OMesh mesh;
  std::vector<OMesh::FaceHandle> faceOf;
  out.facesSplitOff = addTriangles(mesh, welded, weldedTris, faceOf);
  if (mesh.n_faces() > target) {
    mesh.request_vertex_status();
    mesh.request_edge_status();
    mesh.request_face_status();
    mesh.request_face_normals();
    mesh.update_face_normals();
    // First with every outline vertex locked; where that leaves more than the target (a model split
    // into many open sheets, as per-material meshes are: Sibenik's outlines held 27 904 of its 73 556
    // triangles against a budget of 8192), again with the outlines free, still within the tolerance
    // both ways: an outline vertex goes only where the outline stays that near (ModHausdorff), so a
    // straight edge loses its inner vertices and a corner stays.
    for (const bool lockOutline : {true, false}) {
      for (OMesh::VertexHandle v : mesh.vertices())
        mesh.status(v).set_locked(lockOutline && mesh.is_boundary(v));
      out.simplified = decimate(mesh, target, tolerance, nearOriginal) || out.simplified;
      mesh.garbage_collection();  // n_faces() counts deleted faces until then, and so would the next pass
      if (mesh.n_faces() <= target) break;
    }
  }
  out.positions.reserve(mesh.n_vertices());
  for (OMesh::VertexHandle v : mesh.vertices()) {
    const OMesh::Point& p = mesh.point(v);
    out.positions.emplace_back(p[0], p[1], p[2]);
  }
  out.triangles.reserve(mesh.n_faces());
  for (OMesh::FaceHandle f : mesh.faces()) {
    glm::uvec3 t;
    int k = 0;
    for (OMesh::VertexHandle v : mesh.fv_range(f)) t[k++] = uint32_t(v.idx());
    out.triangles.push_back(t);
  }
  return out;
}

Mesh withGeometry(const Mesh& original, const SimplifiedMesh& simplified) {
  Mesh m = original;
  m.positions = simplified.positions;
  m.triangles = simplified.triangles;
  m.normals.clear();
  m.uvs.clear();
  return m;
}

std::vector<SimplifiedMesh> simplifySceneMeshes(const Scene& scene, size_t budget, float tolerance,
                                                const NearSurfaceFactory& nearOriginal) {
  size_t total = 0, small = 0, large = 0;
  for (const Mesh& m : scene.meshes) {
    total += m.triangles.size();
    (m.triangles.size() <= kKeptTriangles ? small : large) += m.triangles.size();
  }
  std::vector<SimplifiedMesh> out;
  out.reserve(scene.meshes.size());
  if (total <= budget) {
    for (const Mesh& m : scene.meshes) out.push_back(SimplifiedMesh{m.positions, m.triangles, 0});
    return out;
  }
  // The large meshes share what the small ones leave, each at least kKeptTriangles.
  const double ratio = budget > small ? double(budget - small) / double(large) : 0.0;
  for (const Mesh& m : scene.meshes) {
    const size_t n = m.triangles.size();
    if (n <= kKeptTriangles) {
      out.push_back(SimplifiedMesh{m.positions, m.triangles, 0});
      continue;
    }
    const size_t target = std::max(kKeptTriangles, size_t(std::ceil(double(n) * ratio)));
    // The mesh is simplified in object space: the tolerance in its units.
    const float stretch = maxStretch(m);
    const float objectTolerance = stretch > 0.0f ? tolerance / stretch : 0.0f;
    out.push_back(
        simplifyMesh(m.positions, m.triangles, target, objectTolerance,
                     nearOriginal ? nearOriginal(m.positions, m.triangles, objectTolerance) : NearSurface()));
  }
  return out;
}

}  // namespace vgi

#pragma GCC diagnostic pop
