#include "traverse/gpu_bvh.h"

#include <embree3/rtcore.h>
#include <glad/gl.h>

#include <algorithm>
#include <cstring>
#include <limits>

#include "core/error.h"
#include "shaders/shared/bindings.glsl"

namespace vgi {

namespace {

// The builder's tree, allocated by Embree's thread-local allocator (freed with the RTCBVH).
struct BuildNode {
  bool leaf;
};
struct InnerNode : BuildNode {
  BuildNode* children[shared::kBvhMaxWidth];
  RTCBounds bounds[shared::kBvhMaxWidth];
};
struct LeafNode : BuildNode {
  unsigned count;
  unsigned prims[RTC_BUILD_MAX_PRIMITIVES_PER_LEAF];
};

void* createNode(RTCThreadLocalAllocator alloc, unsigned childCount, void*) {
  VGI_CHECK(childCount <= shared::kBvhMaxWidth);
  auto* n = static_cast<InnerNode*>(rtcThreadLocalAlloc(alloc, sizeof(InnerNode), 16));
  n->leaf = false;
  for (auto*& c : n->children) c = nullptr;
  return n;
}
void setChildren(void* node, void** children, unsigned count, void*) {
  auto* n = static_cast<InnerNode*>(node);
  for (unsigned i = 0; i < count; ++i) n->children[i] = static_cast<BuildNode*>(children[i]);
}
void setBounds(void* node, const RTCBounds** bounds, unsigned count, void*) {
  auto* n = static_cast<InnerNode*>(node);
  for (unsigned i = 0; i < count; ++i) n->bounds[i] = *bounds[i];
}
void* createLeaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t count, void*) {
  VGI_CHECK(count <= RTC_BUILD_MAX_PRIMITIVES_PER_LEAF);
  auto* l = static_cast<LeafNode*>(rtcThreadLocalAlloc(alloc, sizeof(LeafNode), 16));
  l->leaf = true;
  l->count = unsigned(count);
  for (size_t i = 0; i < count; ++i) l->prims[i] = prims[i].primID;
  return l;
}

glm::vec4 withBits(float x, float y, float z, uint32_t bits) {
  float w;
  std::memcpy(&w, &bits, 4);
  return {x, y, z, w};
}

// Depth-first into the arrays: a node's index is its position in that order.
struct Flattener {
  const FlatScene& scene;
  BvhArrays& out;
  // Child `c` of node `index` (slot already allocated) is `b` with bounds `bounds`.
  void child(size_t index, int c, const BuildNode* b, const RTCBounds& bounds, unsigned depth) {
    uint32_t ref = 0, count = 0;
    if (b->leaf) {
      const auto* l = static_cast<const LeafNode*>(b);
      ref = uint32_t(out.tris.size() / 3);
      count = l->count;
      for (unsigned i = 0; i < l->count; ++i) {
        const uint32_t t = l->prims[i];
        out.tris.push_back(
            withBits(scene.positions[3 * t].x, scene.positions[3 * t].y, scene.positions[3 * t].z, t));
        out.tris.emplace_back(scene.positions[3 * t + 1], 0.0f);
        out.tris.emplace_back(scene.positions[3 * t + 2], 0.0f);
      }
      ++out.leaves;
      out.depth = std::max(out.depth, depth + 1);
    } else {
      ref = uint32_t(out.nodes.size() / stride());
      node(static_cast<const InnerNode*>(b), depth + 1);
    }
    out.nodes[stride() * index + 2 * size_t(c)] =
        withBits(bounds.lower_x, bounds.lower_y, bounds.lower_z, ref);
    out.nodes[stride() * index + 2 * size_t(c) + 1] =
        withBits(bounds.upper_x, bounds.upper_y, bounds.upper_z, count);
  }
  size_t stride() const { return 2 * size_t(out.width); }
  void node(const InnerNode* n, unsigned depth) {
    const size_t index = out.nodes.size() / stride();
    out.nodes.resize(out.nodes.size() + stride());
    for (int c = 0; c < int(out.width); ++c) {
      if (n->children[c])
        child(index, c, n->children[c], n->bounds[c], depth);
      else
        emptyChild(index, c);
    }
  }
  void emptyChild(size_t index, int c) {
    const float inf = std::numeric_limits<float>::infinity();
    out.nodes[stride() * index + 2 * size_t(c)] = withBits(inf, inf, inf, 0);
    out.nodes[stride() * index + 2 * size_t(c) + 1] = withBits(-inf, -inf, -inf, 0);
  }
};

}  // namespace

BvhArrays buildBvh(const FlatScene& scene, const BvhBuildOptions& o) {
  const size_t n = scene.triangleCount();
  if (n >= size_t(std::numeric_limits<uint32_t>::max()) / 3)
    fail("the BVH addresses at most ", std::numeric_limits<uint32_t>::max() / 3, " triangles; the scene has ",
         n);
  if (o.width != 2 && o.width != 4) fail("BVH width ", o.width, ": 2 or 4");
  BvhArrays out;
  out.width = o.width;
  out.normals.reserve(3 * n);
  for (size_t t = 0; t < n; ++t) {
    const glm::vec3* P = &scene.positions[3 * t];
    const glm::vec3 ng = glm::normalize(glm::cross(P[1] - P[0], P[2] - P[0]));  // as the CPU reference
    for (int k = 0; k < 3; ++k) out.normals.emplace_back(scene.normals[3 * t + size_t(k)], ng[k]);
  }
  std::vector<RTCBuildPrimitive> prims;
  prims.reserve(n);
  for (size_t t = 0; t < n; ++t) {
    // Zero area (the corners on a line or a point): no ray hits it, and the
    // watertight test's edge functions there are rounding noise.
    const glm::vec3 a = scene.positions[3 * t];
    if (glm::cross(scene.positions[3 * t + 1] - a, scene.positions[3 * t + 2] - a) == glm::vec3(0.0f)) {
      ++out.dropped;
      continue;
    }
    glm::vec3 lo = scene.positions[3 * t], hi = lo;
    for (int k = 1; k < 3; ++k) {
      lo = glm::min(lo, scene.positions[3 * t + size_t(k)]);
      hi = glm::max(hi, scene.positions[3 * t + size_t(k)]);
    }
    RTCBuildPrimitive p;
    p.lower_x = lo.x, p.lower_y = lo.y, p.lower_z = lo.z, p.geomID = 0;
    p.upper_x = hi.x, p.upper_y = hi.y, p.upper_z = hi.z, p.primID = unsigned(t);
    prims.push_back(p);
  }
  if (prims.empty()) {  // one node of empty children: every ray misses
    out.nodes.resize(2 * size_t(out.width));
    for (int c = 0; c < int(out.width); ++c) Flattener{scene, out}.emptyChild(0, c);
    out.depth = 1;
    return out;
  }
  RTCDevice device = rtcNewDevice(nullptr);
  if (!device) fail("Embree: rtcNewDevice failed (error ", int(rtcGetDeviceError(nullptr)), ")");
  RTCBVH bvh = rtcNewBVH(device);
  RTCBuildArguments args = rtcDefaultBuildArguments();
  args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
  args.maxBranchingFactor = out.width;
  args.maxDepth = shared::bvhMaxDepth(out.width) - 1;
  args.sahBlockSize = 1;
  args.minLeafSize = 1;
  args.maxLeafSize = std::min<unsigned>(std::max(o.maxLeafSize, 1u), RTC_BUILD_MAX_PRIMITIVES_PER_LEAF);
  args.traversalCost = o.traversalCost;
  args.intersectionCost = o.intersectionCost;
  args.bvh = bvh;
  args.primitives = prims.data();
  args.primitiveCount = prims.size();
  args.primitiveArrayCapacity = prims.size();
  args.createNode = createNode;
  args.setNodeChildren = setChildren;
  args.setNodeBounds = setBounds;
  args.createLeaf = createLeaf;
  auto* root = static_cast<BuildNode*>(rtcBuildBVH(&args));
  const RTCError err = rtcGetDeviceError(device);
  if (!root || err != RTC_ERROR_NONE) {
    rtcReleaseBVH(bvh);
    rtcReleaseDevice(device);
    fail("Embree's BVH builder failed (error ", int(err), ") on ", n, " triangles");
  }
  Flattener f{scene, out};
  if (root->leaf) {  // a scene that fits one leaf: a root with it as child 0
    out.nodes.resize(2 * size_t(out.width));
    RTCBounds b{};
    glm::vec3 lo(prims[0].lower_x, prims[0].lower_y, prims[0].lower_z),
        hi(prims[0].upper_x, prims[0].upper_y, prims[0].upper_z);
    for (auto& p : prims) {
      lo = glm::min(lo, glm::vec3(p.lower_x, p.lower_y, p.lower_z));
      hi = glm::max(hi, glm::vec3(p.upper_x, p.upper_y, p.upper_z));
    }
    b.lower_x = lo.x, b.lower_y = lo.y, b.lower_z = lo.z;
    b.upper_x = hi.x, b.upper_y = hi.y, b.upper_z = hi.z;
    f.child(0, 0, root, b, 1);
    for (int c = 1; c < int(out.width); ++c) f.emptyChild(0, c);
  } else {
    f.node(static_cast<const InnerNode*>(root), 1);
  }
  rtcReleaseBVH(bvh);
  rtcReleaseDevice(device);
  return out;
}

nlohmann::json BvhArrays::describe() const {
  return {{"width", width},
          {"nodes", nodes.size() / (2 * size_t(width))},
          {"leaves", leaves},
          {"triangles", tris.size() / 3},
          {"zero_area_dropped", dropped},
          {"depth", depth},
          {"bytes", bytes()}};
}

shared::BvhHit traceBvhCpu(const BvhArrays& bvh, glm::vec3 origin, glm::vec3 dir, float tmax, bool anyHit) {
  return shared::traceBvhWidth(origin, dir, tmax, anyHit, bvh.width, bvh.nodes.data(), bvh.tris.data());
}

GpuBvh::GpuBvh(const BvhArrays& bvh) { upload(bvh); }

void addBvhDefine(ShaderDefines& defines, const GpuBvh& bvh) {
  defines["BVH_WIDTH"] = std::to_string(bvh.width()) + "u";
}

GpuBvh::~GpuBvh() { glDeleteBuffers(3, buffers_); }

void GpuBvh::upload(const BvhArrays& bvh) {
  width_ = bvh.width;
  const std::vector<glm::vec4>* arrays[3] = {&bvh.nodes, &bvh.tris, &bvh.normals};
  bytes_ = 0;
  for (int i = 0; i < 3; ++i) {
    // An empty scene has no triangles: a buffer of one vec4 keeps the binding valid.
    const size_t bytes = std::max<size_t>(arrays[i]->size(), 1) * sizeof(glm::vec4);
    if (bytes != sizes_[i]) {
      if (buffers_[i]) glDeleteBuffers(1, &buffers_[i]);
      glCreateBuffers(1, &buffers_[i]);
      glNamedBufferStorage(buffers_[i], GLsizeiptr(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
      sizes_[i] = bytes;
    }
    if (!arrays[i]->empty())
      glNamedBufferSubData(buffers_[i], 0, GLsizeiptr(arrays[i]->size() * sizeof(glm::vec4)),
                           arrays[i]->data());
    bytes_ += bytes;
  }
}

void GpuBvh::bind() const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_BVH_NODES, buffers_[0]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_BVH_TRIS, buffers_[1]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_BVH_NORMALS, buffers_[2]);
}

}  // namespace vgi
