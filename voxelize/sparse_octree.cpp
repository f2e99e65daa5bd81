#include "voxelize/sparse_octree.h"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>

#include "core/error.h"
#include "core/gpu_memory.h"
#include "core/profiler.h"
#include "core/shader_library.h"
#include "shaders/shared/bindings.glsl"
#include "shaders/shared/sparse_octree.glsl"

namespace vgi {

namespace {
constexpr size_t kBrickTexels = 27, kTexelBytes = 8;  // 3×3×3 RGBA16F
constexpr uint32_t kMaxGroups = 65535;

// A dispatch of `count` invocations of 64 (x·64 + y·65535·64).
void dispatchLinear(uint64_t count) {
  const uint64_t groups = std::max<uint64_t>((count + 63) / 64, 1);
  const uint32_t gx = uint32_t(std::min<uint64_t>(groups, kMaxGroups));
  glDispatchCompute(gx, uint32_t((groups + gx - 1) / gx), 1);
}

uint32_t readCounter(unsigned buffer) {
  uint32_t v = 0;
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  glGetNamedBufferSubData(buffer, 0, 4, &v);
  return v;
}

void setCounter(unsigned buffer, uint32_t v) { glNamedBufferSubData(buffer, 0, 4, &v); }

template <class T>
std::vector<T> readBuffer(unsigned buffer, uint64_t count) {
  std::vector<T> out(count);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  if (count) glGetNamedBufferSubData(buffer, 0, GLsizeiptr(count * sizeof(T)), out.data());
  return out;
}
}  // namespace

uint32_t svoDepth(glm::uvec3 r) {
  const uint32_t side = std::max({r.x, r.y, r.z});
  uint32_t d = 0;
  while ((1u << d) < side) ++d;
  if (d > shared::SVO_MAX_DEPTH)
    fail("parameter 'voxels': ", r.x, "x", r.y, "x", r.z, " with volume=svo: the octree holds at most ",
         1u << shared::SVO_MAX_DEPTH, " cells per axis");
  return std::max(d, 1u);
}

SvoStructure svoReferenceStructure(const std::vector<glm::uvec3>& fragments, uint32_t depth, bool dilate) {
  std::vector<std::set<uint32_t>> flagged(depth + 1), occupied(depth + 1);
  for (const glm::uvec3& f : fragments)
    for (uint32_t l = 0; l <= depth; ++l)
      for (uint32_t k = 0; k < (dilate ? 8u : 1u); ++k) {
        const shared::SvoTarget t = shared::svoFlagTarget(f, l, depth, shared::svoOctantOffset(k));
        if (t.valid) flagged[l].insert(shared::svoPackCell(t.cell));
        if (t.valid && k == 0) occupied[l].insert(shared::svoPackCell(t.cell));
      }
  SvoStructure s;
  s.nodes.push_back(1);
  for (uint32_t l = 0; l <= depth; ++l) {
    s.flagged.emplace_back(flagged[l].begin(), flagged[l].end());
    s.occupied.emplace_back(occupied[l].begin(), occupied[l].end());
    if (l < depth) s.nodes.push_back(8 * uint64_t(flagged[l].size()));
  }
  return s;
}

SparseVoxelOctree::SparseVoxelOctree(const GridBox& box, bool anisotropic, bool dilate)
    : box_(box), anisotropic_(anisotropic), dilate_(dilate), depth_(svoDepth(box.resolution)) {
  counter_ = makeBuffer(4);
}

SparseVoxelOctree::~SparseVoxelOctree() = default;

void SparseVoxelOctree::grow(uint64_t nodes) {
  if (nodes <= capacity_) return;
  const uint64_t cap = std::max<uint64_t>(nodes, capacity_ * 2);
  checkGpuAllocation(double(cap) * 8, "the sparse octree's node pool (" + std::to_string(cap) + " nodes)");
  GlBuffer n = makeBuffer(cap * 4), c = makeBuffer(cap * 4);
  const uint32_t zero = 0;
  glClearNamedBufferData(n.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  if (capacity_) {
    glCopyNamedBufferSubData(nodes_.get(), n.get(), 0, 0, GLsizeiptr(capacity_ * 4));
    glCopyNamedBufferSubData(coords_.get(), c.get(), 0, 0, GLsizeiptr(capacity_ * 4));
  }
  nodes_ = std::move(n);
  coords_ = std::move(c);
  capacity_ = cap;
}

void SparseVoxelOctree::shrink() {
  // The pool grew by doubling while the levels were allocated: keep what the tree holds.
  if (capacity_ <= nodeCount_) return;
  GlBuffer n = makeBuffer(nodeCount_ * 4), c = makeBuffer(nodeCount_ * 4);
  glCopyNamedBufferSubData(nodes_.get(), n.get(), 0, 0, GLsizeiptr(nodeCount_ * 4));
  glCopyNamedBufferSubData(coords_.get(), c.get(), 0, 0, GLsizeiptr(nodeCount_ * 4));
  nodes_ = std::move(n);
  coords_ = std::move(c);
  capacity_ = nodeCount_;
}

void SparseVoxelOctree::build(unsigned words, ShaderLibrary& shaders, Profiler& prof) {
  auto s = prof.scope("svo_build");
  const char* modes[4] = {"COUNT_FRAGMENTS", "WRITE_FRAGMENTS", "FLAG", "ALLOCATE"};
  unsigned progs[4];
  for (int i = 0; i < 4; ++i) {
    ShaderDefines d{{modes[i], "1"}};
    if (i == 2 && dilate_) d["DILATE"] = "1";
    progs[i] = shaders.program({"voxelize/sparse_octree_build.comp.glsl"}, d);
  }
  const glm::uvec3 r = box_.resolution;
  const glm::uvec4 res(r, r.z / 128u);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VOXEL_COUNTER, counter_.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_PYRAMID, words);
  // The fragment list: counted, then written.
  setCounter(counter_.get(), 0);
  glUseProgram(progs[0]);
  shaders.setUniform(progs[0], "uResolution", res);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  glDispatchCompute((r.x + 3) / 4, (r.y + 3) / 4, (r.z / 32 + 3) / 4);
  fragments_ = readCounter(counter_.get());
  checkGpuAllocation(double(std::max<uint64_t>(fragments_, 1)) * 4, "the sparse octree's fragment list");
  GlBuffer fragments = makeBuffer(std::max<uint64_t>(fragments_, 1) * 4);
  setCounter(counter_.get(), 0);
  glUseProgram(progs[1]);
  shaders.setUniform(progs[1], "uResolution", res);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_SVO_FRAGMENTS, fragments.get());
  glDispatchCompute((r.x + 3) / 4, (r.y + 3) / 4, (r.z / 32 + 3) / 4);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  // The nodes, level by level: flag, allocate (the new tiles are already 0).
  capacity_ = 0;
  nodes_ = GlBuffer();
  coords_ = GlBuffer();
  grow(std::max<uint64_t>(64, fragments_ / 2));
  levels_ = {{0, 1}};
  uint64_t tiles = 1;  // tile 0: the root
  for (uint32_t l = 0; l <= depth_; ++l) {
    glUseProgram(progs[2]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_SVO_NODES, nodes_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_SVO_COORDS, coords_.get());
    shaders.setUniform(progs[2], "uLevel", l);
    shaders.setUniform(progs[2], "uDepth", depth_);
    shaders.setUniform(progs[2], "uCount", uint32_t(fragments_));
    dispatchLinear(fragments_);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    if (l == depth_) break;
    glUseProgram(progs[3]);
    setCounter(counter_.get(), uint32_t(tiles));
    const uint64_t first = levels_[l].first, count = levels_[l].second - first;
    shaders.setUniform(progs[3], "uFirst", uint32_t(first));
    shaders.setUniform(progs[3], "uCount", uint32_t(count));
    dispatchLinear(count);
    const uint64_t newTiles = readCounter(counter_.get());
    if (newTiles * 8 > shared::SVO_CHILD_MASK)
      fail("the sparse octree of ", box_.resolution.x, "x", box_.resolution.y, "x", box_.resolution.z,
           " needs more than 2^31 nodes");
    levels_.emplace_back(tiles * 8, newTiles * 8);
    tiles = newTiles;
    grow(tiles * 8);
  }
  nodeCount_ = levels_.back().second;
  leafFirst_ = levels_[depth_].first;
  shrink();
  allocatePools();
}

SparseVoxelOctree::Pool SparseVoxelOctree::makePool(uint64_t bricks, uint32_t base) const {
  GLint max3d = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3d);
  const uint64_t axis = uint64_t(max3d) / shared::SVO_BRICK;
  Pool p;
  p.base = base;
  bricks = std::max<uint64_t>(bricks, 1);
  // About a cube of bricks: the last slice is the only one partly used.
  p.bricks.x = uint32_t(std::min<uint64_t>(uint64_t(std::ceil(std::cbrt(double(bricks)))), axis));
  p.bricks.y =
      uint32_t(std::min<uint64_t>(uint64_t(std::ceil(std::sqrt(double(bricks) / double(p.bricks.x)))), axis));
  const uint64_t z = (bricks + uint64_t(p.bricks.x) * p.bricks.y - 1) / (uint64_t(p.bricks.x) * p.bricks.y);
  if (z > axis)
    fail("the sparse octree's brick pool: ", bricks, " bricks exceed a 3D texture of ", max3d,
         "³ (GL_MAX_3D_TEXTURE_SIZE)");
  p.bricks.z = uint32_t(z);
  const glm::uvec3 size = p.bricks * shared::SVO_BRICK;
  checkGpuAllocation(double(size.x) * size.y * size.z * kTexelBytes, "the sparse octree's brick pool");
  unsigned t = 0;
  glCreateTextures(GL_TEXTURE_3D, 1, &t);
  glTextureStorage3D(t, 1, GL_RGBA16F, GLsizei(size.x), GLsizei(size.y), GLsizei(size.z));
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  for (GLenum w : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glTextureParameteri(t, w, GL_CLAMP_TO_EDGE);
  const float zero[4] = {0, 0, 0, 0};
  glClearTexImage(t, 0, GL_RGBA, GL_FLOAT, zero);
  p.texture = GlTexture(t);
  return p;
}

void SparseVoxelOctree::allocatePools() {
  const uint32_t tiles = uint32_t(nodeCount_ / 8), leafTiles = uint32_t(leafFirst_ / 8);
  for (Pool& f : faces_) f = Pool();
  if (anisotropic_) {
    iso_ = makePool(tiles - leafTiles, leafTiles);
    for (Pool& f : faces_) f = makePool(leafTiles, 0);
  } else {
    iso_ = makePool(tiles, 0);
  }
}

void SparseVoxelOctree::resolve(unsigned counts, unsigned sums, float radianceMax, ShaderLibrary& shaders,
                                Profiler& prof) {
  // One dispatch over level `level`'s nodes: input `in` (or none), outputs `outs` at
  // IMAGE_OUTPUT + k (pools of one layout: the face pools, or the iso pool alone).
  auto pass = [&](unsigned prog, uint32_t level, const Pool* in, std::vector<const Pool*> outs) {
    const Pool& out = *outs[0];
    glUseProgram(prog);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_SVO_NODES, nodes_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_SVO_COORDS, coords_.get());
    const uint64_t first = levels_[level].first, count = levels_[level].second - first;
    shaders.setUniform(prog, "uFirst", uint32_t(first));
    shaders.setUniform(prog, "uCount", uint32_t(count));
    shaders.setUniform(prog, "uLevel", level);
    shaders.setUniform(prog, "uOutBricks", out.bricks);
    shaders.setUniform(prog, "uOutBase", out.base);
    shaders.setUniform(prog, "uInBricks", in ? in->bricks : glm::uvec3(1));
    shaders.setUniform(prog, "uInBase", in ? in->base : 0u);
    if (in) glBindTextureUnit(TEXUNIT_PASS_INPUT, in->texture.get());
    for (size_t k = 0; k < outs.size(); ++k)
      glBindImageTexture(GLuint(IMAGE_OUTPUT + k), outs[k]->texture.get(), 0, GL_TRUE, 0, GL_READ_WRITE,
                         GL_RGBA16F);
    dispatchLinear(count);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  };
  const std::string file = "voxelize/sparse_octree_filter.comp.glsl";
  {
    auto s = prof.scope("svo_resolve");
    ShaderDefines d{{"RESOLVE", "1"}};
    if (!counts) d["RADIANCE_NONE"] = "1";
    const unsigned prog = shaders.program({file}, d);
    if (counts) {
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VALUE_COUNTS, counts);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VALUE_RADIANCE, sums);
      shaders.setUniform(prog, "uRadianceMax", radianceMax);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    pass(prog, depth_, nullptr, {&iso_});
  }
  {
    auto s = prof.scope("svo_filter");
    ShaderDefines d{{"FILTER", "1"}};
    if (anisotropic_) d["ANISOTROPIC"] = "1";
    const unsigned prog = shaders.program({file}, d);
    for (int l = int(depth_) - 1; l >= 0; --l) {
      if (!anisotropic_) {
        pass(prog, uint32_t(l), &iso_, {&iso_});
        continue;
      }
      for (uint32_t f = 0; f < 6; ++f) {
        shaders.setUniform(prog, "uFace", f);
        pass(prog, uint32_t(l), l + 1 == int(depth_) ? &iso_ : &faces_[f], {&faces_[f]});
      }
    }
  }
  auto s = prof.scope("svo_borders");
  // One pass per level for all the pools that hold it: a tile's neighbours are found once.
  const unsigned one = shaders.program({file}, {{"BORDERS", "1"}, {"POOLS", "1"}});
  const unsigned six = shaders.program({file}, {{"BORDERS", "1"}, {"POOLS", "6"}});
  for (uint32_t m = 1; m <= depth_; ++m) {
    // The tiles of level m are the children of level m − 1's nodes.
    if (!anisotropic_ || m == depth_)
      pass(one, m - 1, nullptr, {&iso_});
    else
      pass(six, m - 1, nullptr, {&faces_[0], &faces_[1], &faces_[2], &faces_[3], &faces_[4], &faces_[5]});
  }
}

void SparseVoxelOctree::bind(ShaderLibrary& shaders, unsigned prog) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_SVO_NODES, nodes_.get());
  glBindTextureUnit(TEXUNIT_VALUE_RADIANCE, iso_.texture.get());
  if (anisotropic_)
    for (unsigned f = 0; f < 6; ++f) glBindTextureUnit(TEXUNIT_VALUE_ANISO + f, faces_[f].texture.get());
  shaders.setUniform(prog, "uSvoDepth", depth_);
  shaders.setUniform(prog, "uSvoLeafFirst", uint32_t(leafFirst_));
  shaders.setUniform(prog, "uSvoIsoBricks", iso_.bricks);
  shaders.setUniform(prog, "uSvoFaceBricks", anisotropic_ ? faces_[0].bricks : glm::uvec3(1));
  shaders.setUniform(prog, "uSvoIsoBase", iso_.base);
}

size_t SparseVoxelOctree::bytes() const {
  auto pool = [](const Pool& p) {
    return size_t(p.bricks.x) * p.bricks.y * p.bricks.z * kBrickTexels * kTexelBytes;
  };
  size_t b = size_t(capacity_) * 8 + pool(iso_);
  for (const Pool& f : faces_) b += pool(f);
  return b;
}

nlohmann::json SparseVoxelOctree::describe() const {
  nlohmann::json levels = nlohmann::json::array();
  for (uint32_t l = 0; l <= depth_; ++l) {
    const uint64_t nodes = levels_[l].second - levels_[l].first;
    // The bricks holding level l's values: its tiles (the root: brick 0).
    const uint64_t bricks = l == 0 ? 1 : nodes / 8;
    const uint64_t pools = (!anisotropic_ || l == depth_) ? 1 : 6;
    levels.push_back({{"level", l},
                      {"nodes", nodes},
                      {"bricks", bricks},
                      {"bytes", double(nodes) * 8 + double(bricks * pools * kBrickTexels * kTexelBytes)}});
  }
  return {{"storage", "svo"},
          {"depth", depth_},
          {"dilate", dilate_},
          {"mips", anisotropic_ ? "anisotropic" : "isotropic"},
          {"fragments", fragments_},
          {"nodes", nodeCount_},
          {"leaves", leafCount()},
          {"bricks", nodeCount_ / 8},
          {"brick", "3x3x3 rgba16f (2x2x2 children + the +side border)"},
          {"levels", levels},
          {"bytes", bytes()}};
}

SvoStructure SparseVoxelOctree::readStructure() const {
  const std::vector<uint32_t> nodes = readBuffer<uint32_t>(nodes_.get(), nodeCount_);
  const std::vector<uint32_t> coords = readBuffer<uint32_t>(coords_.get(), nodeCount_);
  SvoStructure s;
  for (uint32_t l = 0; l <= depth_; ++l) {
    std::vector<uint32_t> f, o;
    for (uint64_t n = levels_[l].first; n < levels_[l].second; ++n) {
      const uint32_t child = shared::svoChild(nodes[n]);
      if (l < depth_ ? child >= shared::SVO_TILE : child == shared::SVO_FLAGGED) f.push_back(coords[n]);
      if (shared::svoOccupied(nodes[n])) o.push_back(coords[n]);
    }
    std::sort(f.begin(), f.end());
    std::sort(o.begin(), o.end());
    s.flagged.push_back(f);
    s.occupied.push_back(o);
    s.nodes.push_back(levels_[l].second - levels_[l].first);
  }
  return s;
}

namespace {
// Every node's cell, from its parent's (nodes without children have no coords of their own).
std::vector<uint32_t> nodeCells(const std::vector<uint32_t>& nodes) {
  std::vector<uint32_t> cells(nodes.size(), 0);
  for (size_t n = 0; n < nodes.size(); ++n)
    if (shared::svoChild(nodes[n]) >= shared::SVO_TILE) {
      const glm::uvec3 c = shared::svoUnpackCell(n == 0 ? 0u : cells[n]);
      for (uint32_t o = 0; o < 8; ++o)
        cells[shared::svoChild(nodes[n]) + o] = shared::svoPackCell(2u * c + shared::svoOctantOffset(o));
    }
  return cells;
}
}  // namespace

std::vector<uint32_t> SparseVoxelOctree::readLeafCells() const {
  const std::vector<uint32_t> nodes = readBuffer<uint32_t>(nodes_.get(), nodeCount_);
  const std::vector<uint32_t> cells = nodeCells(nodes);
  return std::vector<uint32_t>(cells.begin() + std::ptrdiff_t(leafFirst_), cells.end());
}

uint64_t SparseVoxelOctree::countUnreachedLeaves(unsigned counts) const {
  const std::vector<uint32_t> nodes = readBuffer<uint32_t>(nodes_.get(), nodeCount_);
  const std::vector<uint32_t> n = readBuffer<uint32_t>(counts, leafCount());
  uint64_t holes = 0;
  for (uint64_t i = 0; i < n.size(); ++i) holes += shared::svoOccupied(nodes[leafFirst_ + i]) && n[i] == 0;
  return holes;
}

std::map<uint32_t, glm::vec4> SparseVoxelOctree::readLevel(uint32_t level, int face) const {
  if (level > depth_ || face < -1 || face > 5 || (face >= 0 && !anisotropic_) ||
      (anisotropic_ && (face < 0) != (level == depth_)))
    fail("no sparse-octree level ", level, " of ", face < 0 ? "the iso pool" : "a face pool");
  const Pool& p = face < 0 ? iso_ : faces_[face];
  const glm::uvec3 size = p.bricks * shared::SVO_BRICK;
  std::vector<glm::vec4> texels(size_t(size.x) * size.y * size.z);
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  glGetTextureImage(p.texture.get(), 0, GL_RGBA, GL_FLOAT, GLsizei(texels.size() * 16), texels.data());
  const std::vector<uint32_t> nodes = readBuffer<uint32_t>(nodes_.get(), nodeCount_);
  const std::vector<uint32_t> cells = nodeCells(nodes);
  std::map<uint32_t, glm::vec4> out;
  for (uint64_t n = levels_[level].first; n < levels_[level].second; ++n) {
    const glm::uvec3 t = n == 0 ? glm::uvec3(1u)
                                : shared::svoBrickOrigin(uint32_t(n >> 3) - p.base, p.bricks) +
                                      shared::svoOctantOffset(uint32_t(n & 7));
    out[cells[n]] = texels[(size_t(t.z) * size.y + t.y) * size.x + t.x];
  }
  return out;
}

}  // namespace vgi
