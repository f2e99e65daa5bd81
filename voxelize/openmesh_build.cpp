#include "voxelize/openmesh_build.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <OpenMesh/Core/System/omstream.hh>

namespace vgi {

long addTriangles(OMesh& mesh, const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& tris,
                  std::vector<OMesh::FaceHandle>& faceOf) {
  long splitOff = 0;
  omerr().disable();  // refused faces are expected here and handled below
  std::vector<OMesh::VertexHandle> vh(positions.size());
  for (size_t i = 0; i < positions.size(); ++i)
    vh[i] = mesh.add_vertex(OMesh::Point(positions[i].x, positions[i].y, positions[i].z));
  faceOf.assign(tris.size(), OMesh::FaceHandle());
  for (size_t t = 0; t < tris.size(); ++t) {
    const glm::uvec3& f = tris[t];
    OMesh::FaceHandle fh;
    if (f[0] != f[1] && f[1] != f[2] && f[0] != f[2]) fh = mesh.add_face(vh[f[0]], vh[f[1]], vh[f[2]]);
    if (!fh.is_valid()) {  // non-manifold or degenerate: its own vertices
      // From `positions`, not mesh.point(): that is a reference into the
      // vertex array, which add_vertex may reallocate before it copies.
      auto point = [&](uint32_t i) { return OMesh::Point(positions[i].x, positions[i].y, positions[i].z); };
      OMesh::VertexHandle a = mesh.add_vertex(point(f[0])), b = mesh.add_vertex(point(f[1])),
                          c = mesh.add_vertex(point(f[2]));
      fh = mesh.add_face(a, b, c);
      ++splitOff;
    }
    faceOf[t] = fh;
  }
  omerr().enable();
  return splitOff;
}

}  // namespace vgi

#pragma GCC diagnostic pop
