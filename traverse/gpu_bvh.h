// A BVH over a flattened scene's triangles in the layout the shared GLSL/C++
// kernel traverses (shaders/shared/trace_bvh.glsl: binary, both children's
// boxes in the parent, Aila & Laine 2009), built on the CPU by Embree's BVH
// builder API (rtcBuildBVH: binned SAH, our node and leaf callbacks), and its
// upload into two SSBOs. The same arrays run the kernel compiled as C++
// (traceBvhCpu) and as GLSL (tracer=bvh), so the tests compare the two bit for bit.
#pragma once
#include <cstddef>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/scene.h"
#include "core/shader_library.h"
#include "shaders/shared/trace_bvh.glsl"

namespace vgi {

struct BvhBuildOptions {
  unsigned width = shared::kBvhDefaultWidth;  // children per node: 2 (Aila & Laine) or 4 (a wide BVH)
  unsigned maxLeafSize = 4;                   // triangles per leaf at most
  float traversalCost = 1.0f;                 // SAH: a node's cost against
  float intersectionCost = 1.0f;              // a triangle's
};

struct BvhArrays {
  unsigned width = 2;            // children per node
  std::vector<glm::vec4> nodes;  // 2·width per node (trace_bvh.glsl)
  std::vector<glm::vec4> tris;   // 3 per triangle, in leaf order
  // 3 per triangle, in the flattened scene's order (BvhHit::triangle): the corners' shading
  // normals in xyz, the unit geometric normal (corner 0 → 1 × 0 → 2) in the three w.
  std::vector<glm::vec4> normals;
  size_t leaves = 0;
  size_t dropped = 0;  // triangles of zero area, left out
  unsigned depth = 0;  // of the deepest leaf (root = 1)
  size_t bytes() const { return (nodes.size() + tris.size() + normals.size()) * sizeof(glm::vec4); }
  nlohmann::json describe() const;  // nodes, leaves, triangles, depth, bytes
};

// Throws if the scene has more triangles than 32-bit ids address.
BvhArrays buildBvh(const FlatScene& scene, const BvhBuildOptions& options = {});

// The shared kernel on the CPU (what the GLSL pass runs).
shared::BvhHit traceBvhCpu(const BvhArrays& bvh, glm::vec3 origin, glm::vec3 dir, float tmax, bool anyHit);

class GpuBvh;
// The define a program that traces `bvh` is compiled with (BVH_WIDTH).
void addBvhDefine(ShaderDefines& defines, const GpuBvh& bvh);

// The arrays on the GPU, bound at BINDING_BVH_NODES / BINDING_BVH_TRIS / BINDING_BVH_NORMALS.
class GpuBvh {
 public:
  explicit GpuBvh(const BvhArrays& bvh);
  ~GpuBvh();
  GpuBvh(const GpuBvh&) = delete;
  GpuBvh& operator=(const GpuBvh&) = delete;
  void upload(const BvhArrays& bvh);  // the same sizes or others (buffers made again)
  void bind() const;
  size_t bytes() const { return bytes_; }
  unsigned width() const { return width_; }

 private:
  unsigned width_ = 2;
  unsigned buffers_[3] = {0, 0, 0};
  size_t sizes_[3] = {0, 0, 0}, bytes_ = 0;
};

}  // namespace vgi
