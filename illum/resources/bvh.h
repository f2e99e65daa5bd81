// Resource kind "bvh": the scene flattened into world-space triangles
// (FlatScene) in an Embree BVH on the CPU (traverse/embree_tracer.h), and the
// area lights of those triangles (Emitters: an emitter's index follows the
// BVH's primitive ids). Rebuilt for each time of a scene with dynamic meshes.
// What the exact counterparts and the exact-visibility variants trace.
#pragma once
#include <nlohmann/json.hpp>

#include "illum/framework/resources.h"

namespace vgi {

struct BvhNeed {
  static constexpr const char* kKind = "bvh";
  static const ResourceKind& row();  // its row of the kinds table (bvhKind())
  nlohmann::json key() const { return nlohmann::json::object(); }
};

ResourceKind bvhKind();

}  // namespace vgi
