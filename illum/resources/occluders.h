// The occluder geometry of a scene (resource kind "occluders"): its meshes
// simplified to a triangle budget (voxelize/mesh_simplify.h), uploaded as
// world-space positions (vertex attribute 0, non-indexed), for passes that draw
// the scene many times and need only what it hides — `avg`'s VPL shadow maps.
// A scene within the budget is drawn as it is. Dynamic meshes are simplified
// once in object space and moved with the scene (setTime).
#pragma once
#include <nlohmann/json.hpp>
#include <vector>

#include "core/scene.h"
#include "illum/framework/resources.h"
#include "voxelize/mesh_simplify.h"

namespace vgi {

// The simplification's test of the new faces against the original surface
// (voxelize/mesh_simplify.h): an Embree BVH of the mesh, a ray each way along
// the normal, as long as the tolerance.
NearSurfaceFactory nearSurfaceByEmbree();

class Occluders {
 public:
  Occluders(const Scene& scene, size_t budgetTriangles, float tolerance, float time);
  ~Occluders();
  Occluders(const Occluders&) = delete;
  Occluders& operator=(const Occluders&) = delete;

  void setTime(float time);                       // re-uploads the dynamic meshes' triangles
  void drawInstanced(int instances) const;        // all triangles, `instances` times (gl_InstanceID)
  unsigned vertexBuffer() const { return vbo_; }  // 3 world-space vec3 corners per triangle
  size_t triangleCount() const { return triangles_; }
  // The distance the drawn triangles may be from the scene's: the need's
  // tolerance where a mesh was simplified, else 0 (a shadow test's bias).
  float tolerance() const { return tolerance_; }
  // triangles (scene, drawn), budget, budget_met (drawn within 10 % of the budget), tolerance,
  // faces kept apart, the simplification's ms.
  nlohmann::json stats() const { return stats_; }

 private:
  Scene occluders_;            // the simplified meshes only (no materials or textures), as the scene's
  std::vector<size_t> first_;  // each mesh's first triangle in the buffer
  size_t triangles_ = 0;
  float tolerance_ = 0.0f;
  unsigned vao_ = 0, vbo_ = 0;
  nlohmann::json stats_;
};

// About `triangles` triangles, no point of the scene farther than
// `tolerance` (world units) from them; within the budget, the scene as it is.
struct OccluderNeed {
  static constexpr const char* kKind = "occluders";
  static const ResourceKind& row();  // its row of the kinds table (occludersKind())
  size_t triangles = 8192;
  float tolerance = 0.0f;
  nlohmann::json key() const { return {{"triangles", triangles}, {"tolerance", tolerance}}; }
};

ResourceKind occludersKind();

}  // namespace vgi
