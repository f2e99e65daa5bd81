#pragma once
// Smooth per-corner normals for meshes that come without them, in time linear in
// the corner count (issue 33, class 10).
//
// The rule is assimp's aiProcess_GenSmoothNormals with a maximum smoothing angle
// (which the loader used before): a corner's normal is the normalised sum of the
// unit face normals of every corner at the same position whose face normal lies
// within the angle of its own face's (cos >= cos(angle), its own included).
// One difference: where triangles share a vertex in the imported mesh (the two
// halves of a triangulated quad, an indexed mesh) assimp gave the vertex one
// face normal, the last written, and summed it once; here every triangle's
// corner counts (a non-planar quad's diagonal gets the mean of both halves).
// assimp finds those corners by a spatial sort that, for each corner, walks all
// corners at the position: quadratic where many coincide (10^4 copies of one
// triangle took 2 s, 10^6 never finished). Here corners are grouped by their exact
// position, and within a position by their exact face normal (a cluster with a
// count); positions closer than assimp's epsilon (1e-4 of the mesh's diagonal)
// are found through a hash grid of that cell size, and the angle test runs once
// per pair of *distinct* normals: copies of a triangle, or a fan of coplanar
// triangles, cost one test. A position whose neighbourhood holds more than
// `maxDistinctNormals` clusters (the apex of a cone of thousands of facets)
// keeps its faces' flat normals instead, which bounds the work at
// maxDistinctNormals per cluster; `flatPositions` counts those positions.

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace vgi {

struct SmoothNormals {
  std::vector<glm::vec3> normals;  // one per corner (3 per triangle); 0 for a zero-area triangle
  long flatPositions = 0;          // positions left flat (more distinct normals than the bound)
};

// One normal per corner of `triangles` (indices into `positions`; shared or not).
SmoothNormals smoothCornerNormals(const std::vector<glm::vec3>& positions,
                                  const std::vector<glm::uvec3>& triangles, float maxAngleDegrees,
                                  int maxDistinctNormals);

// One normal per vertex again: each vertex of `triangles` split by the normals its corners got (a
// vertex on a crease becomes one vertex per side), shared wherever its corners agree — as assimp's
// JoinIdenticalVertices left a mesh after GenSmoothNormals, so that what follows the mesh's
// connectivity (the atlas's charts) still sees it connected.
struct WeldedNormals {
  std::vector<uint32_t> source;       // per new vertex: the vertex of the input it copies
  std::vector<glm::vec3> normals;     // per new vertex
  std::vector<glm::uvec3> triangles;  // the input's triangles on the new vertices
};
WeldedNormals weldCornerNormals(const std::vector<glm::uvec3>& triangles,
                                const std::vector<glm::vec3>& cornerNormals);

}  // namespace vgi
