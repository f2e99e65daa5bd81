// Occluder meshes: a scene's meshes simplified for passes that only need what
// they hide, not how they look — the many VPL shadow maps of `avg` (the AVG
// paper, §IV, draws its VPL maps from a 7000-triangle Sibenik).
//
// Quadric edge collapses (Garland and Heckbert 1997, "Surface Simplification
// Using Quadric Error Metrics"; OpenMesh's decimater) on each mesh with its
// corners welded by position, with two guards for occlusion:
//   - boundary vertices stay locked in a first pass: an open sheet (a wall, a
//     window's frame) keeps its outline, so the simplified mesh does not shrink
//     away from where it met other geometry and let light leak between them;
//     where that pass leaves the mesh over its target (a model of many open
//     sheets: Sibenik's per-material meshes held 27 904 triangles against 8192)
//     a second one frees them, under the same tolerance, so an outline moves
//     by at most that (22 461 on Sibenik; tests/voxelize/mesh_simplify_test.cpp
//     measures what it lets through);
//   - no collapse flips a face's normal (ModNormalFlipping);
//   - both ways within `tolerance`: every point a collapse removes stays that
//     near the new faces (ModHausdorff), and the new faces stay that near the
//     original surface — their centroids and edge midpoints, tested by the
//     caller's `nearOriginal` (an Embree BVH of the mesh, illum/occluders).
//     ModHausdorff alone bounds only the first: measured on Sibenik, 23 % of
//     the point pairs that see each other in the scene were blocked by faces
//     it let cut in front of the surface, 1.7 % with both (tests/voxelize/
//     mesh_simplify_test.cpp). A shadow test against the simplified mesh then
//     needs a bias of about `tolerance`.
// Non-manifold faces stay as they are (voxelize/openmesh_build.h).
#pragma once
#include <functional>
#include <glm/glm.hpp>
#include <vector>

namespace vgi {

struct Mesh;
struct Scene;

struct SimplifiedMesh {
  std::vector<glm::vec3> positions;  // object space, as the mesh's
  std::vector<glm::uvec3> triangles;
  long facesSplitOff = 0;   // non-manifold faces kept apart (not simplified)
  bool simplified = false;  // edges were collapsed
};

// Whether the original surface passes within the tolerance of point p along
// ±n (n: the unit normal of the new face p lies on).
using NearSurface = std::function<bool(const glm::vec3& p, const glm::vec3& n)>;
// Makes the NearSurface test of one mesh (object space).
using NearSurfaceFactory = std::function<NearSurface(
    const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& triangles, float tolerance)>;

// One mesh down to about `targetTriangles` (more where the guards stop it; a
// mesh already at or under the target comes back as it is, welded).
SimplifiedMesh simplifyMesh(const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& triangles,
                            size_t targetTriangles, float tolerance, const NearSurface& nearOriginal);

// Every mesh of `scene`, the budget shared in proportion to their triangle
// counts, each within `tolerance` in world units (in object space: divided by
// the most its transform, animation included, stretches a length); meshes of at most kKeptTriangles triangles stay whole (a box stays a
// box), as does a scene within the budget (then each mesh is its own triangles,
// in order, unwelded: the same geometry the scene draws).
constexpr size_t kKeptTriangles = 32;
std::vector<SimplifiedMesh> simplifySceneMeshes(const Scene& scene, size_t budgetTriangles, float tolerance,
                                                const NearSurfaceFactory& nearOriginal);

// `original` (its transform, animation and material) with the simplified
// geometry: no normals or uvs (flattenMesh then uses the face normals).
Mesh withGeometry(const Mesh& original, const SimplifiedMesh& simplified);

}  // namespace vgi
