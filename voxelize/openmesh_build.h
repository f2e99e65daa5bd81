// The OpenMesh half-edge mesh of an indexed triangle list, shared by the chart
// segmentation (voxelize/chart_segmentation) and the occluder simplification
// (voxelize/mesh_simplify). Included by .cpp files of voxelize/ only.
//
// Non-manifold input (complex edges or vertices) makes OpenMesh refuse faces;
// those are added with duplicated vertices, so they become separate components
// and no triangle is dropped (a degenerate one, with a repeated index, too).
#pragma once
// GCC 12 reports a false -Wmaybe-uninitialized inside OpenMesh's property
// containers (vector<VectorT>::push_back); it is not in this project's code.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#pragma GCC diagnostic pop
#include <glm/glm.hpp>
#include <vector>

namespace vgi {

using OMesh = OpenMesh::TriMesh_ArrayKernelT<>;

// Adds positions and triangles to `mesh` (empty); faceOf[t] is triangle t's
// face. Returns how many faces were split off.
long addTriangles(OMesh& mesh, const std::vector<glm::vec3>& positions,
                  const std::vector<glm::uvec3>& triangles, std::vector<OMesh::FaceHandle>& faceOf);

}  // namespace vgi
