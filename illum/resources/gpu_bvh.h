// Resource kind "gpu_bvh": the scene's triangles in a BVH on the GPU
// (traverse/gpu_bvh.h: built by Embree's BVH builder on the CPU, in the
// layout of shaders/shared/trace_bvh.glsl), what tracer=bvh traces: exact
// visibility on the same device as the voxel tracers. A scene with dynamic
// meshes builds it again for each time (a refit would keep the topology:
// not done; the stats give the build time). Offers the GpuBvh and its
// BvhArrays (the same arrays the C++ kernel runs).
#pragma once
#include <nlohmann/json.hpp>

#include "illum/framework/resources.h"

namespace vgi {

struct GpuBvhNeed {
  static constexpr const char* kKind = "gpu_bvh";
  static const ResourceKind& row();  // its row of the kinds table (gpuBvhKind())
  nlohmann::json key() const { return nlohmann::json::object(); }
};

ResourceKind gpuBvhKind();

}  // namespace vgi
