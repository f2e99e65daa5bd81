// Atlas-based voxelization — Thiedemann et al., "Voxel-based Global
// Illumination", I3D 2011, §3.1: each mesh is rendered once into its texture
// atlas, writing world positions (unused texels stay invalid); then one point
// per valid texel sets the bit of its cell (binary), and, for multi-valued
// grids, adds its normal / albedo / glossy values to its cell's sums (averaged
// by count, as in Bashford-Rogers et al., AVG). §3.2: static meshes are
// voxelized once; each frame copies that grid and inserts the dynamic meshes.
//
// The atlas holds positions as offsets from the grid's origin, not world
// positions: far from the world's origin (georeferenced coordinates) a float's
// step is a large part of a cell, and interpolating world positions snapped
// every point of a unit box at 10^7 onto its corners (recall 0.00008).
//
// Sliver triangles may cover no texel centre when filled, so the atlas is drawn
// three times — corners as points, edges as lines (pulled back onto their
// triangle), then the filled triangles on top, which keep the regular lattice
// the density rule relies on. Reported per mesh: "triangles_without_texels"
// (no written texel on or within half a texel of the triangle: lost) and
// "triangles_sampled_by_neighbours" (slivers covered by adjacent triangles).
//
// Parameters (VoxelizeRequest)
// | field           | default | meaning                                                         |
// |-----------------|---------|-----------------------------------------------------------------|
// | texelsPerVoxel  | 2√2     | texel = smallest voxel edge / this (rule: grid_metrics.h)       |
// | atlasResolution | 0       | manual square atlas size per mesh (0 = from texelsPerVoxel)      |
// | atlasCacheDir   | ""      | where atlases are cached by content hash ("" = no cache)        |
// | valueGrids      | {}      | multi-valued grids to build: normal, albedo, glossy              |
#include "voxelize/atlas_voxelizer.h"

#include <glad/gl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/gl_context.h"
#include "core/gpu_scene.h"
#include "core/shader_library.h"
#include "shaders/shared/atlas_footprint.glsl"
#include "shaders/shared/bindings.glsl"
#include "shaders/shared/value_grid.glsl"
#include "voxelize/atlas.h"
#include "voxelize/gpu_grid.h"

namespace vgi {

void insertAtlasPoints(const AtlasSamples& atlas, BinaryGrid& grid) {
  const shared::GridParams g = grid.box().params();
  for (size_t i = 0; i < atlas.positions.size(); ++i) {
    const glm::vec4& p = atlas.positions[i];
    if (p.w == 0.0f) continue;
    shared::PointBit b = shared::pointBit(g, glm::vec3(p));
    if (b.word == 0xffffffffu) continue;  // outside the grid: no footprint either
    grid.words()[b.word] |= b.bit;
    const int tri = atlas.triangles.empty() ? -1 : atlas.triangles[i];
    if (atlas.footprint <= 0.0f || tri < 0) continue;
    glm::vec3 a = shared::offsetToGrid(g, atlas.corners[3 * size_t(tri)]);
    glm::vec3 bb = shared::offsetToGrid(g, atlas.corners[3 * size_t(tri) + 1]);
    glm::vec3 c = shared::offsetToGrid(g, atlas.corners[3 * size_t(tri) + 2]);
    shared::CellRange r = shared::footprintCells(g, shared::offsetToGrid(g, glm::vec3(p)), atlas.footprint);
    for (int z = r.lo.z; z <= r.hi.z; ++z)
      for (int y = r.lo.y; y <= r.hi.y; ++y)
        for (int x = r.lo.x; x <= r.hi.x; ++x)
          if (shared::triangleOverlapsBox(glm::vec3(x, y, z) + 0.5f, glm::vec3(0.5f), a, bb, c))
            grid.set(uint32_t(x), uint32_t(y), uint32_t(z));
  }
}

// Object → offset from the grid's origin, where the atlas keeps its points (atlas_render.vert.glsl).
// Composed in double, so that a far translation and the grid's origin cancel before rounding.
glm::mat4 modelToBox(const glm::mat4& objectToWorld, const GridBox& box) {
  return glm::mat4(glm::translate(glm::dmat4(1.0), -glm::dvec3(box.origin)) * glm::dmat4(objectToWorld));
}

constexpr int kVertexFloats = 11;  // position 3, atlas uv 2, triangle 1, normal 3, texture uv 2

// Per-cell point counts and fixed-point sums of the requested channels.
struct AtlasVoxelizer::ValueBuffers {
  size_t cells = 0;
  unsigned counts = 0;
  unsigned sums[3] = {0, 0, 0};  // normal, albedo, glossy (0 = not built)
  ValueBuffers(size_t n, const std::vector<std::string>& channels) : cells(n) {
    const uint32_t zero = 0;
    auto make = [&](size_t bytes) {
      unsigned b = 0;
      glCreateBuffers(1, &b);
      glNamedBufferStorage(b, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
      glClearNamedBufferData(b, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
      return b;
    };
    counts = make(n * 4);
    for (size_t k = 0; k < 3; ++k)
      for (auto& ch : channels)
        if (ch == valueChannelNames()[k]) sums[k] = make(n * 16);
  }
  ~ValueBuffers() {
    glDeleteBuffers(1, &counts);
    for (unsigned s : sums)
      if (s) glDeleteBuffers(1, &s);
  }
  // Cells [first, end) (linear, valueIndex's order).
  void copyTo(const ValueBuffers& o, size_t first, size_t end) const {
    glCopyNamedBufferSubData(counts, o.counts, GLintptr(first * 4), GLintptr(first * 4),
                             GLsizeiptr((end - first) * 4));
    for (int k = 0; k < 3; ++k)
      if (sums[k])
        glCopyNamedBufferSubData(sums[k], o.sums[k], GLintptr(first * 16), GLintptr(first * 16),
                                 GLsizeiptr((end - first) * 16));
  }
  void bind() const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VALUE_COUNTS, counts);
    for (unsigned k = 0; k < 3; ++k)
      if (sums[k]) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VALUE_NORMAL + k, sums[k]);
  }
};

struct AtlasVoxelizer::MeshGpu {
  std::string name;
  int material = 0;
  bool dynamic = false;
  glm::mat4 model0{1.0f};  // object → world at time 0 (the atlas's frame)
  const Mesh* mesh = nullptr;
  std::vector<glm::vec2> uv;  // the atlas, 3 per triangle
  int resolution = 0;
  float texelWorld = 0;  // world length of one texel of this mesh's atlas
  GLsizei corners = 0, lineIndices = 0;
  unsigned vao = 0, vbo = 0, ebo = 0;
  // A dynamic mesh's atlas, drawn once in object space (position, triangle; with values normal,
  // albedo, glossy): each frame moves its points by the mesh's transform instead of drawing it again.
  unsigned kept[5] = {0, 0, 0, 0, 0};
  // The kept atlas's texels that hold a point (x | y << 16): its insertions run one invocation per point.
  unsigned keptPoints = 0;
  GLsizei keptCount = 0;
};

AtlasVoxelizer::AtlasVoxelizer(const VoxelizeRequest& req, Profiler& prof,
                               std::vector<AtlasSamples>* atlasPoints)
    : request_(req) {
  VGI_CHECK(req.gl && req.shaders);
  if (!(req.atlasFootprint >= 0.0f && req.atlasFootprint <= 4.0f))
    fail("atlas footprint ", req.atlasFootprint, ": must be in [0, 4] texels");
  createPrograms();
  createGrids();
  GLint maxTex = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTex);
  const float texel = autoTexelWorld(req.box.voxelSize(), req.texelsPerVoxel);
  nlohmann::json atlases = nlohmann::json::array();
  double atlasMs = 0;
  int staticCount = 0, dynamicCount = 0;
  for (const Mesh& mesh : req.scene->meshes) {
    atlases.push_back(addMesh(mesh, texel, maxTex, prof, atlasMs));
    (meshes_.back()->dynamic ? dynamicCount : staticCount)++;
  }
  createTargets();
  const glm::ivec2 coverage = insertStaticMeshes(prof, atlases, atlasPoints);
  stats_["atlas_resolution"] = maxResolution_;
  stats_["atlases"] = atlases;
  stats_["atlas_build_ms"] = atlasMs;
  stats_["texel_world"] = texel;
  stats_["texels_per_voxel"] = req.texelsPerVoxel;
  stats_["atlas_footprint_texels"] = req.atlasFootprint;
  stats_["triangles_without_texels"] = coverage.x;
  stats_["triangles_sampled_by_neighbours"] = coverage.y;
  stats_["static_meshes"] = staticCount;
  stats_["dynamic_meshes"] = dynamicCount;
}

// The render and insertion programs (and, for multi-valued grids, the value and radiance ones).
void AtlasVoxelizer::createPrograms() {
  const VoxelizeRequest& req = request_;
  const bool values = !req.valueGrids.empty();
  ShaderDefines renderDefs{{"ATLAS_VERTEX_FLOATS", std::to_string(kVertexFloats)}};
  if (values) renderDefs["MULTI_VALUED"] = "1";
  renderProg_ = req.shaders->program({"voxelize/atlas_render.vert.glsl", "voxelize/atlas_render.frag.glsl"},
                                     renderDefs);
  insertProg_ = req.shaders->program({"voxelize/atlas_insert.comp.glsl"},
                                     {{"ATLAS_VERTEX_FLOATS", std::to_string(kVertexFloats)}});
  setGridUniforms(*req.shaders, insertProg_, req.box);
  if (values) {
    const uint64_t cells = req.box.cellCount();
    const double bytes =
        double(cells) * (4.0 + 16.0 * double(req.valueGrids.size())) * 2.0;  // static + frame (+ radiance)
    const double phys = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
    if (bytes > 0.5 * phys)
      fail("multi-valued grids (", req.valueGrids.size(), " channels) at ", req.box.resolution.x, "x",
           req.box.resolution.y, "x", req.box.resolution.z, " need ", bytes / (1 << 20),
           " MiB; this machine has ", phys / (1 << 20), " MiB (at most half is used)");
    ShaderDefines valueDefs;
    for (auto& ch : req.valueGrids)
      if (ch != "radiance")
        valueDefs["VALUE_" + std::string(ch == "normal"   ? "NORMAL"
                                         : ch == "albedo" ? "ALBEDO"
                                                          : "GLOSSY")] = "1";
    valueDefs["ATLAS_VERTEX_FLOATS"] = std::to_string(kVertexFloats);
    valueDefs["INSERT_BITS"] = "1";  // the binary insertion in the same pass
    valueProg_ = req.shaders->program({"voxelize/atlas_insert_values.comp.glsl"}, valueDefs);
    setGridUniforms(*req.shaders, valueProg_, req.box);
    if (std::find(req.valueGrids.begin(), req.valueGrids.end(), "radiance") != req.valueGrids.end()) {
      ShaderDefines rd = renderDefs;
      rd["VALUE_RADIANCE"] = "1";
      radianceRenderProg_ =
          req.shaders->program({"voxelize/atlas_render.vert.glsl", "voxelize/atlas_render.frag.glsl"}, rd);
      radianceInsertProg_ = req.shaders->program(
          {"voxelize/atlas_insert_values.comp.glsl"},
          {{"VALUE_RADIANCE", "1"}, {"ATLAS_VERTEX_FLOATS", std::to_string(kVertexFloats)}});
      setGridUniforms(*req.shaders, radianceInsertProg_, req.box);
      const uint32_t zero = 0;
      glCreateBuffers(1, &radianceSums_);
      glNamedBufferStorage(radianceSums_, GLsizeiptr(cells * 16), nullptr, GL_DYNAMIC_STORAGE_BIT);
      glClearNamedBufferData(radianceSums_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
      glCreateBuffers(1, &radianceMaxBuffer_);
      glNamedBufferStorage(radianceMaxBuffer_, 4, &zero, GL_DYNAMIC_STORAGE_BIT);
    }
    staticValues_ = std::make_unique<ValueBuffers>(size_t(cells), req.valueGrids);
    frameValues_ = std::make_unique<ValueBuffers>(size_t(cells), req.valueGrids);
    materials_ = std::make_unique<GpuScene>(*req.scene, 0.0f);
  }
}

// The static and frame grids (and value sums) and their point counters.
void AtlasVoxelizer::createGrids() {
  const VoxelizeRequest& req = request_;
  static_ = std::make_unique<GpuGridBuffer>(req.box);
  frame_ = std::make_unique<GpuGridBuffer>(req.box);
  const uint32_t zero = 0;
  for (unsigned* counter : {&staticCounter_, &frameCounter_}) {
    glCreateBuffers(1, counter);
    glNamedBufferStorage(*counter, 4, &zero, GL_DYNAMIC_STORAGE_BIT);
  }
}

// Builds (or reads from the cache) the mesh's atlas at time 0 and uploads its
// corners; returns the atlas's stats.
nlohmann::json AtlasVoxelizer::addMesh(const Mesh& mesh, float texel, int maxTex, Profiler& prof,
                                       double& atlasMs) {
  const VoxelizeRequest& req = request_;
  auto m = std::make_unique<MeshGpu>();
  m->name = mesh.name;
  m->mesh = &mesh;
  m->material = mesh.material;
  m->dynamic = mesh.dynamic && !mesh.keyframes.empty();
  // The atlas comes from the mesh at time 0: rigid motion keeps lengths, so a
  // dynamic mesh keeps its (cached) atlas while it moves.
  m->model0 = mesh.objectToWorld(0.0f);
  std::vector<glm::vec3> p0(mesh.positions.size());
  for (size_t i = 0; i < p0.size(); ++i) p0[i] = glm::vec3(m->model0 * glm::vec4(mesh.positions[i], 1.0f));
  AtlasOptions ao;
  ao.texelWorld = texel;
  ao.resolution = req.atlasResolution;
  ao.cacheDir = req.atlasCacheDir;
  MeshAtlas atlas;
  {
    auto s = prof.scope("atlas_build");
    atlas = buildAtlas(p0, mesh.triangles, ao, maxTex);
  }
  atlasMs += atlas.ms;
  m->resolution = atlas.resolution;
  m->uv = atlas.uv;
  m->texelWorld = atlas.texelWorld;
  // Position (RGBA32F) + triangle id (R32I) per texel; refuse before GL's allocation fails.
  const double bytes = double(atlas.resolution) * atlas.resolution * 20.0;
  if (bytes > double(1u << 31))
    fail("atlas voxelizer: mesh '", mesh.name, "' needs a ", atlas.resolution, "x", atlas.resolution,
         " atlas (", bytes / (1 << 20), " MiB of render targets, limit 2048 MiB); lower --texels-per-voxel (",
         req.texelsPerVoxel, ") or the grid resolution, or set --atlas-resolution");
  maxResolution_ = std::max(maxResolution_, atlas.resolution);
  nlohmann::json aj = atlas.toJson();
  aj["mesh"] = mesh.name;
  aj["triangles"] = mesh.triangles.size();
  aj["dynamic"] = m->dynamic;

  uploadCorners(*m);
  meshes_.push_back(std::move(m));
  return aj;
}

// The mesh's corners (position, atlas uv, triangle id, normal, texture uv) and its atlas edges, uploaded.
void AtlasVoxelizer::uploadCorners(MeshGpu& m) const {
  const Mesh& mesh = *m.mesh;
  std::vector<float> verts;
  verts.reserve(mesh.triangles.size() * 3 * kVertexFloats);
  std::vector<uint32_t> lines;
  lines.reserve(mesh.triangles.size() * 6);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3& tri = mesh.triangles[t];
    glm::vec3 face = glm::cross(mesh.positions[tri[1]] - mesh.positions[tri[0]],
                                mesh.positions[tri[2]] - mesh.positions[tri[0]]);
    for (int k = 0; k < 3; ++k) {
      const glm::vec3& p = mesh.positions[tri[k]];
      const glm::vec2& uv = m.uv[3 * t + size_t(k)];
      glm::vec3 n =
          mesh.normals.empty() || mesh.normals[tri[k]] == glm::vec3(0.0f) ? face : mesh.normals[tri[k]];
      glm::vec2 tex = mesh.uvs.empty() ? glm::vec2(0.0f) : mesh.uvs[tri[k]];
      verts.insert(verts.end(), {p.x, p.y, p.z, uv.x, uv.y, float(t), n.x, n.y, n.z, tex.x, tex.y});
    }
    uint32_t b = uint32_t(3 * t);
    lines.insert(lines.end(), {b, b + 1, b + 1, b + 2, b + 2, b});
  }
  m.corners = GLsizei(3 * mesh.triangles.size());
  m.lineIndices = GLsizei(lines.size());
  glCreateVertexArrays(1, &m.vao);
  glCreateBuffers(1, &m.vbo);
  glCreateBuffers(1, &m.ebo);
  glNamedBufferStorage(m.vbo, GLsizeiptr(std::max<size_t>(verts.size(), 1) * sizeof(float)), verts.data(), 0);
  glNamedBufferStorage(m.ebo, GLsizeiptr(std::max<size_t>(lines.size(), 1) * sizeof(uint32_t)), lines.data(),
                       0);
  glVertexArrayVertexBuffer(m.vao, 0, m.vbo, 0, kVertexFloats * sizeof(float));
  glVertexArrayElementBuffer(m.vao, m.ebo);
  const int sizes[5] = {3, 2, 1, 3, 2}, offsets[5] = {0, 3, 5, 6, 9};
  for (unsigned a = 0; a < 5; ++a) {
    glEnableVertexArrayAttrib(m.vao, a);
    glVertexArrayAttribFormat(m.vao, a, sizes[a], GL_FLOAT, GL_FALSE, unsigned(offsets[a]) * sizeof(float));
    glVertexArrayAttribBinding(m.vao, a, 0);
  }
}

// One atlas target, as large as the largest atlas; each mesh uses its corner.
void AtlasVoxelizer::createTargets() {
  const VoxelizeRequest& req = request_;
  const bool values = !req.valueGrids.empty();
  const int R = std::max(maxResolution_, 1);
  glCreateTextures(GL_TEXTURE_2D, 2, targets_);
  glTextureStorage2D(targets_[0], 1, GL_RGBA32F, R, R);
  glTextureStorage2D(targets_[1], 1, GL_R32I, R, R);
  // An integer texture with the default (linear) filters is incomplete and
  // reads as 0 even through texelFetch.
  for (unsigned t : targets_) {
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  glCreateFramebuffers(1, &fbo_);
  glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, targets_[0], 0);
  glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT1, targets_[1], 0);
  if (values) {
    glCreateTextures(GL_TEXTURE_2D, 3, valueTargets_);
    for (int k = 0; k < 3; ++k) {
      glTextureStorage2D(valueTargets_[k], 1, GL_RGBA32F, R, R);
      glNamedFramebufferTexture(fbo_, GLenum(GL_COLOR_ATTACHMENT2 + k), valueTargets_[k], 0);
    }
    if (radianceSums_) {
      glCreateTextures(GL_TEXTURE_2D, 1, &radianceTarget_);
      glTextureStorage2D(radianceTarget_, 1, GL_RGBA32F, R, R);
      glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT5, radianceTarget_, 0);
    }
  }
  const GLenum bufs[5] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                          GL_COLOR_ATTACHMENT3, GL_COLOR_ATTACHMENT4};
  glNamedFramebufferDrawBuffers(fbo_, values ? 5 : 2, bufs);
  if (glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    fail("atlas voxelizer: the ", R, "x", R, " atlas framebuffer is incomplete on ", req.gl->renderer());
}

// Static meshes into the static grid, once; every mesh's texel coverage is
// measured here (into `atlases`); returns the triangles without texels and
// those sampled by their neighbours' texels.
glm::ivec2 AtlasVoxelizer::insertStaticMeshes(Profiler& prof, nlohmann::json& atlases,
                                              std::vector<AtlasSamples>* atlasPoints) {
  const VoxelizeRequest& req = request_;
  long lost = 0, sharedTotal = 0;
  for (size_t i = 0; i < meshes_.size(); ++i) {
    if (meshes_[i]->dynamic) keepAtlas(*meshes_[i], prof);
    const MeshGpu& m = *meshes_[i];
    std::vector<int> ids;
    AtlasSamples* points = nullptr;
    if (atlasPoints) {
      atlasPoints->emplace_back();
      points = &atlasPoints->back();
    }
    // Dynamic meshes are only measured here (into the frame grid, which each frame overwrites).
    renderAndInsert(m, m.dynamic ? req.time : 0.0f, m.dynamic ? *frame_ : *static_,
                    m.dynamic ? frameValues_.get() : staticValues_.get(),
                    m.dynamic ? frameCounter_ : staticCounter_, prof, &ids, points);
    // A triangle is lost when no written texel lies on it or within half a
    // texel of it in the atlas. Slivers inside a chart often own no texel (the
    // neighbours' fill covers those centres) but are sampled by that lattice.
    const int R = m.resolution;
    std::vector<char> owns(m.mesh->triangles.size(), 0);
    for (int id : ids)
      if (id >= 0 && size_t(id) < owns.size()) owns[size_t(id)] = 1;
    long meshLost = 0, sharing = 0;
    for (size_t t = 0; t < owns.size(); ++t) {
      if (owns[t]) continue;
      glm::vec2 lo = glm::min(m.uv[3 * t], glm::min(m.uv[3 * t + 1], m.uv[3 * t + 2])) * float(R);
      glm::vec2 hi = glm::max(m.uv[3 * t], glm::max(m.uv[3 * t + 1], m.uv[3 * t + 2])) * float(R);
      bool near = false;
      for (int y = std::max(0, int(std::floor(lo.y - 0.5f))); !near && y <= std::min(R - 1, int(hi.y + 0.5f));
           ++y)
        for (int x = std::max(0, int(std::floor(lo.x - 0.5f)));
             !near && x <= std::min(R - 1, int(hi.x + 0.5f)); ++x)
          near = ids[size_t(y) * size_t(R) + size_t(x)] >= 0;
      (near ? sharing : meshLost)++;
    }
    atlases[i]["triangles_without_texels"] = meshLost;
    atlases[i]["triangles_sampled_by_neighbours"] = sharing;
    lost += meshLost;
    sharedTotal += sharing;
  }
  return {int(lost), int(sharedTotal)};
}

double AtlasVoxelizer::gpuBytes() const {
  const double cells = double(request_.box.cellCount());
  double bytes = double(static_->bytes()) + double(frame_->bytes());
  for (const ValueBuffers* v : {staticValues_.get(), frameValues_.get()}) {
    if (!v) continue;
    bytes += cells * 4.0;
    for (unsigned s : v->sums) bytes += s ? cells * 16.0 : 0.0;
  }
  if (radianceSums_) bytes += cells * 16.0;
  const double R = double(std::max(maxResolution_, 1));
  bytes += R * R * (16.0 + 4.0);  // position + triangle id
  if (valueTargets_[0]) bytes += R * R * 16.0 * 3.0;
  if (radianceTarget_) bytes += R * R * 16.0;
  for (const auto& m : meshes_) {
    bytes += double(m->corners) * kVertexFloats * 4.0 + double(m->lineIndices) * 4.0;
    const double r = double(m->resolution);
    if (m->kept[0]) bytes += r * r * (16.0 + 4.0 + (m->kept[2] ? 16.0 * 3.0 : 0.0));
  }
  return bytes;
}

AtlasVoxelizer::~AtlasVoxelizer() {
  for (auto& m : meshes_) {
    unsigned b[2] = {m->vbo, m->ebo};
    glDeleteBuffers(2, b);
    glDeleteVertexArrays(1, &m->vao);
    glDeleteTextures(5, m->kept);  // (0 names are ignored)
    glDeleteBuffers(1, &m->keptPoints);
  }
  glDeleteFramebuffers(1, &fbo_);
  glDeleteTextures(2, targets_);
  if (valueTargets_[0]) glDeleteTextures(3, valueTargets_);
  if (radianceTarget_) glDeleteTextures(1, &radianceTarget_);
  if (radianceSums_) glDeleteBuffers(1, &radianceSums_);
  if (radianceMaxBuffer_) glDeleteBuffers(1, &radianceMaxBuffer_);
  glDeleteBuffers(1, &staticCounter_);
  glDeleteBuffers(1, &frameCounter_);
}

// What shaders/voxelize/atlas_point_cells.glsl reads: the atlas targets, the
// mesh's corners and model matrix, the footprint radius.
// A dynamic mesh's points are its kept atlas's (object space) moved by uPointModel; a static
// mesh's are the targets' (drawn at their place: uPointModel = identity, which changes no bit).
void AtlasVoxelizer::setPointCellInputs(unsigned program, const MeshGpu& m, float time) const {
  const glm::mat4 model = modelToBox(m.mesh->objectToWorld(time), request_.box);
  const bool kept = m.kept[0] != 0;
  ShaderLibrary& sh = *request_.shaders;
  sh.setUniform(program, "uFootprint", request_.atlasFootprint * m.texelWorld);
  sh.setUniform(program, "uModel", model);
  sh.setUniform(program, "uPointModel", kept ? model : glm::mat4(1.0f));
  glBindTextureUnit(TEXUNIT_ATLAS_POSITION, kept ? m.kept[0] : targets_[0]);
  glBindTextureUnit(TEXUNIT_ATLAS_TRIANGLE, kept ? m.kept[1] : targets_[1]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_ATLAS_CORNERS, m.vbo);
  // A kept atlas's points are listed (the buffer bound either way: never read unlisted).
  sh.setUniform(program, "uListed", kept ? int(m.keptCount) : 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_ATLAS_POINTS, kept ? m.keptPoints : m.vbo);
}

namespace {
// The insertion's workgroups: 8 × 8 texels over the atlas, or 64 listed points each (uListed).
void dispatchPoints(int resolution, GLsizei listed) {
  if (listed <= 0) {
    glDispatchCompute(unsigned(resolution + 7) / 8, unsigned(resolution + 7) / 8, 1);
    return;
  }
  const unsigned groups = (unsigned(listed) + 63u) / 64u, x = std::min(groups, 65535u);
  glDispatchCompute(x, (groups + x - 1) / x, 1);
}
}  // namespace

void AtlasVoxelizer::keepAtlas(MeshGpu& m, Profiler& prof) {
  auto s = prof.scope("atlas_render");
  const bool values = valueTargets_[0] != 0;
  const int R = m.resolution, n = values ? 5 : 2;
  glUseProgram(renderProg_);
  if (values) {
    materials_->bind(*request_.shaders, renderProg_);
    request_.shaders->setUniform(renderProg_, "uMaterial", m.material);
  }
  renderAtlas(m, glm::mat4(1.0f), renderProg_, n);
  const unsigned from[5] = {targets_[0], targets_[1], valueTargets_[0], valueTargets_[1], valueTargets_[2]};
  const GLenum formats[5] = {GL_RGBA32F, GL_R32I, GL_RGBA32F, GL_RGBA32F, GL_RGBA32F};
  glCreateTextures(GL_TEXTURE_2D, n, m.kept);
  for (int k = 0; k < n; ++k) {
    glTextureStorage2D(m.kept[k], 1, formats[k], R, R);
    glTextureParameteri(m.kept[k], GL_TEXTURE_MIN_FILTER, GL_NEAREST);  // (an integer texture needs it)
    glTextureParameteri(m.kept[k], GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glCopyImageSubData(from[k], GL_TEXTURE_2D, 0, 0, 0, 0, m.kept[k], GL_TEXTURE_2D, 0, 0, 0, 0, R, R, 1);
  }
  // The texels holding a point, once (the kept atlas does not change): read back a band of rows at a
  // time, listed in texel order, uploaded.
  std::vector<uint32_t> points;
  const int band = std::max(1, std::min(R, (1 << 22) / std::max(R, 1)));  // ≤ 64 MiB of texels a read
  std::vector<glm::vec4> pos;
  for (int y0 = 0; y0 < R; y0 += band) {
    const int rows = std::min(band, R - y0);
    pos.resize(size_t(rows) * size_t(R));
    glGetTextureSubImage(m.kept[0], 0, 0, y0, 0, R, rows, 1, GL_RGBA, GL_FLOAT,
                         GLsizei(pos.size() * sizeof(glm::vec4)), pos.data());
    for (int y = 0; y < rows; ++y)
      for (int x = 0; x < R; ++x)
        if (pos[size_t(y) * size_t(R) + size_t(x)].w != 0.0f)
          points.push_back(uint32_t(x) | (uint32_t(y0 + y) << 16));
  }
  m.keptCount = GLsizei(points.size());
  glCreateBuffers(1, &m.keptPoints);
  glNamedBufferStorage(m.keptPoints, GLsizeiptr(std::max<size_t>(points.size(), 1) * 4),
                       points.empty() ? nullptr : points.data(), 0);
}

void AtlasVoxelizer::renderAtlas(const MeshGpu& m, const glm::mat4& model, unsigned prog, int targets) const {
  const int R = m.resolution;
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  const GLenum bufs[6] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                          GL_COLOR_ATTACHMENT3, GL_COLOR_ATTACHMENT4, GL_COLOR_ATTACHMENT5};
  glNamedFramebufferDrawBuffers(fbo_, targets, bufs);
  glViewport(0, 0, R, R);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  const float clearPos[4] = {0, 0, 0, 0};
  const int clearId[4] = {-1, -1, -1, -1};
  glClearBufferfv(GL_COLOR, 0, clearPos);
  glClearBufferiv(GL_COLOR, 1, clearId);
  for (int k = 2; k < targets; ++k) glClearBufferfv(GL_COLOR, k, clearPos);
  request_.shaders->setUniform(prog, "uModel", model);
  glBindVertexArray(m.vao);
  // Corners and edges first, the fill last: a texel whose centre a triangle
  // covers keeps that centre's point (the regular lattice the resolution
  // rule relies on); the others hold edge or corner points of slivers.
  ShaderLibrary& sh = *request_.shaders;
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_ATLAS_CORNERS, m.vbo);
  sh.setUniform(prog, "uClampToTriangle", 0);
  glDrawArrays(GL_POINTS, 0, m.corners);
  sh.setUniform(prog, "uClampToTriangle", 1);  // line fragments overshoot the edge's ends
  glDrawElements(GL_LINES, m.lineIndices, GL_UNSIGNED_INT, nullptr);
  sh.setUniform(prog, "uClampToTriangle", 0);
  glDrawArrays(GL_TRIANGLES, 0, m.corners);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void AtlasVoxelizer::insertRadiance(float time, const std::function<void(unsigned)>& bindLights,
                                    Profiler& prof) {
  if (!radianceSums_) fail("internal: insertRadiance without a requested radiance channel");
  const uint32_t zero = 0;
  {
    // Pass 1: the largest radiance of any atlas point (the fixed-point range).
    auto s = prof.scope("radiance_max");
    glClearNamedBufferData(radianceMaxBuffer_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glUseProgram(radianceRenderProg_);
    materials_->bind(*request_.shaders, radianceRenderProg_);
    bindLights(radianceRenderProg_);
    request_.shaders->setUniform(radianceRenderProg_, "uShadowBias", 1.0f);
    request_.shaders->setUniform(radianceRenderProg_, "uGridOrigin", request_.box.origin);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VALUE_RADIANCE_MAX, radianceMaxBuffer_);
    for (auto& m : meshes_) {
      request_.shaders->setUniform(radianceRenderProg_, "uMaterial", m->material);
      renderAtlas(*m, modelToBox(m->mesh->objectToWorld(time), request_.box), radianceRenderProg_, 6);
    }
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    uint32_t bits = 0;
    glGetNamedBufferSubData(radianceMaxBuffer_, 0, 4, &bits);
    std::memcpy(&radianceMax_, &bits, 4);
    // An unlit scene keeps a positive range (its sums are 0 anyway).
    if (!(radianceMax_ > 0.0f) || !std::isfinite(radianceMax_)) radianceMax_ = 1.0f;
  }
  auto s = prof.scope("radiance_insert");
  glClearNamedBufferData(radianceSums_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  for (auto& m : meshes_) {
    glUseProgram(radianceRenderProg_);
    request_.shaders->setUniform(radianceRenderProg_, "uMaterial", m->material);
    renderAtlas(*m, modelToBox(m->mesh->objectToWorld(time), request_.box), radianceRenderProg_, 6);
    glUseProgram(radianceInsertProg_);
    request_.shaders->setUniform(radianceInsertProg_, "uAtlasSize", glm::ivec2(m->resolution));
    request_.shaders->setUniform(radianceInsertProg_, "uRadianceMax", radianceMax_);
    setPointCellInputs(radianceInsertProg_, *m, time);
    glBindTextureUnit(TEXUNIT_ATLAS_RADIANCE, radianceTarget_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VALUE_RADIANCE, radianceSums_);
    dispatchPoints(m->resolution, m->kept[0] ? m->keptCount : 0);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  }
  stats_["radiance_max"] = radianceMax_;
}

void AtlasVoxelizer::renderAndInsert(const MeshGpu& m, float time, const GpuGridBuffer& target,
                                     const ValueBuffers* values, unsigned counter, Profiler& prof,
                                     std::vector<int>* ids, AtlasSamples* points) {
  const int R = m.resolution;
  const bool kept = m.kept[0] != 0;  // a dynamic mesh: its points move, nothing is drawn
  if (!kept) {
    auto s = prof.scope("atlas_render");
    glUseProgram(renderProg_);
    if (values) {
      materials_->bind(*request_.shaders, renderProg_);
      request_.shaders->setUniform(renderProg_, "uMaterial", m.material);
    }
    renderAtlas(m, modelToBox(m.mesh->objectToWorld(time), request_.box), renderProg_, values ? 5 : 2);
  }
  if (!values) {
    auto s = prof.scope("insertion");
    glUseProgram(insertProg_);
    request_.shaders->setUniform(insertProg_, "uAtlasSize", glm::ivec2(R));
    setPointCellInputs(insertProg_, m, time);
    target.bind(BINDING_GRID_WORDS);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VOXEL_COUNTER, counter);
    dispatchPoints(R, kept ? m.keptCount : 0);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  } else {
    // The bits and the values in one pass (INSERT_BITS).
    auto s = prof.scope("insertion_values");
    glUseProgram(valueProg_);
    target.bind(BINDING_GRID_WORDS);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VOXEL_COUNTER, counter);
    request_.shaders->setUniform(valueProg_, "uAtlasSize", glm::ivec2(R));
    setPointCellInputs(valueProg_, m, time);
    const unsigned units[3] = {TEXUNIT_ATLAS_NORMAL, TEXUNIT_ATLAS_ALBEDO, TEXUNIT_ATLAS_GLOSSY};
    for (unsigned k = 0; k < 3; ++k) glBindTextureUnit(units[k], kept ? m.kept[2 + k] : valueTargets_[k]);
    // Kept normals are the object's: turned by the transform's normal matrix.
    const glm::mat4 model = modelToBox(m.mesh->objectToWorld(time), request_.box);
    request_.shaders->setUniform(
        valueProg_, "uNormalModel",
        kept ? glm::mat4(glm::transpose(glm::inverse(glm::mat3(model)))) : glm::mat4(1.0f));
    request_.shaders->setUniform(valueProg_, "uTurnNormals", kept ? 1 : 0);
    values->bind();
    dispatchPoints(R, kept ? m.keptCount : 0);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  }
  const unsigned positions = kept ? m.kept[0] : targets_[0], triangles = kept ? m.kept[1] : targets_[1];
  if (ids) {
    ids->assign(size_t(R) * size_t(R), -1);
    glGetTextureSubImage(triangles, 0, 0, 0, 0, R, R, 1, GL_RED_INTEGER, GL_INT,
                         GLsizei(ids->size() * sizeof(int)), ids->data());
  }
  if (points) {
    const glm::mat4 model = modelToBox(m.mesh->objectToWorld(time), request_.box);
    points->positions.assign(size_t(R) * size_t(R), glm::vec4(0.0f));
    glGetTextureSubImage(positions, 0, 0, 0, 0, R, R, 1, GL_RGBA, GL_FLOAT,
                         GLsizei(points->positions.size() * sizeof(glm::vec4)), points->positions.data());
    if (kept)  // the points where the insertion put them (atlas_point_cells.glsl: uPointModel)
      for (glm::vec4& p : points->positions)
        if (p.w != 0.0f) p = glm::vec4(glm::vec3(model * glm::vec4(glm::vec3(p), 1.0f)), p.w);
    points->triangles.assign(size_t(R) * size_t(R), -1);
    glGetTextureSubImage(triangles, 0, 0, 0, 0, R, R, 1, GL_RED_INTEGER, GL_INT,
                         GLsizei(points->triangles.size() * sizeof(int)), points->triangles.data());
    points->corners.clear();
    for (const glm::uvec3& tri : m.mesh->triangles)
      for (int k = 0; k < 3; ++k)
        points->corners.push_back(glm::vec3(model * glm::vec4(m.mesh->positions[tri[k]], 1.0f)));
    points->footprint = request_.atlasFootprint * m.texelWorld;
  }
}

// The cells the dynamic meshes' points and footprints can reach at `time`: their bounds, widened
// by the largest footprint radius and a cell (rounding), through the grid's axes.
CellRange AtlasVoxelizer::dynamicCells(float time) const {
  Bounds b;
  float footprint = 0;
  for (auto& m : meshes_)
    if (m->dynamic) {
      const glm::mat4 M = m->mesh->objectToWorld(time);
      for (const glm::vec3& p : m->mesh->positions) b.extend(glm::vec3(M * glm::vec4(p, 1.0f)));
      footprint = std::max(footprint, request_.atlasFootprint * m->texelWorld);
    }
  const glm::vec3 v = request_.box.voxelSize();
  const int reach = int(std::ceil(footprint / std::min({v.x, v.y, v.z})));
  return boundsCells(request_.box, b, 1 + reach, 2 + reach);
}

void AtlasVoxelizer::voxelizeFrame(float time, Profiler& prof) {
  {
    auto s = prof.scope("copy");
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    // The frame grid holds the static grid and the dynamic meshes as the last frame inserted them:
    // the static grid is copied back over the cells those could reach (rows of the grid's words,
    // slices of the value sums); the first frame copies all of it.
    const glm::uvec3 n = request_.box.resolution;
    const CellRange all{glm::uvec3(0), n};
    const CellRange r = framed_ ? dynamicCells(framedAt_) : all;
    restoredCells_ = r.count();
    if (r.count() > 0) {
      const GLintptr row = GLintptr(n.x) * 16;  // one grid row of one slab: n.x RGBA32UI words
      for (uint32_t slab = r.lo.z / 128; slab < (r.hi.z + 127) / 128; ++slab) {
        const GLintptr first = (GLintptr(slab) * n.y + r.lo.y) * row;
        glCopyNamedBufferSubData(static_->buffer(), frame_->buffer(), first, first,
                                 GLsizeiptr(r.hi.y - r.lo.y) * row);
      }
      if (staticValues_)
        staticValues_->copyTo(*frameValues_, size_t(r.lo.z) * n.x * n.y, size_t(r.hi.z) * n.x * n.y);
    }
    const uint32_t zero = 0;
    glClearNamedBufferData(frameCounter_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  }
  framed_ = true;
  framedAt_ = time;
  for (auto& m : meshes_)
    if (m->dynamic)
      renderAndInsert(*m, time, *frame_, frameValues_.get(), frameCounter_, prof, nullptr, nullptr);
}

BinaryGrid AtlasVoxelizer::readFrame() const {
  BinaryGrid grid(request_.box);
  frame_->read(grid);
  return grid;
}

ValueSumBuffers AtlasVoxelizer::valueBuffers() const {
  ValueSumBuffers b;
  if (!frameValues_) return b;
  b.counts = frameValues_->counts;
  for (int k = 0; k < 3; ++k) b.sums[k] = frameValues_->sums[k];
  b.sums[3] = radianceSums_;
  b.radianceMax = radianceMax_;
  return b;
}

ValueGrids AtlasVoxelizer::readValues() const {
  ValueGrids g;
  g.box = request_.box;
  g.channels = request_.valueGrids;
  if (!frameValues_) return g;
  const size_t cells = frameValues_->cells;
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  g.counts.resize(cells);
  glGetNamedBufferSubData(frameValues_->counts, 0, GLsizeiptr(cells * 4), g.counts.data());
  std::vector<uint32_t> sums(cells * 4);
  for (auto& ch : g.channels) {
    const uint32_t k = valueChannelIndex(ch);
    glGetNamedBufferSubData(k == shared::VALUE_CHANNEL_RADIANCE ? radianceSums_ : frameValues_->sums[k], 0,
                            GLsizeiptr(cells * 16), sums.data());
    g.means.push_back(decodeMeans(sums, g.counts, ch, radianceMax_));
  }
  return g;
}

nlohmann::json AtlasVoxelizer::stats() const {
  nlohmann::json s = stats_;
  uint32_t staticPoints = 0, framePoints = 0;
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(staticCounter_, 0, 4, &staticPoints);
  glGetNamedBufferSubData(frameCounter_, 0, 4, &framePoints);
  s["points"] = staticPoints + framePoints;  // of the last frame, static meshes included
  s["restored_cells"] = restoredCells_;      // the static grid copied back over these at the last frame
  return s;
}

BinaryGrid voxelizeAtlasGl(const VoxelizeRequest& req, Profiler& prof, nlohmann::json& stats,
                           std::vector<AtlasSamples>* atlasPoints) {
  AtlasVoxelizer v(req, prof, atlasPoints);
  v.voxelizeFrame(req.time, prof);
  BinaryGrid grid(req.box);
  {
    auto s = prof.scope("readback");
    v.frameGrid().read(grid);
  }
  stats.update(v.stats());  // (items() of a temporary would dangle)
  return grid;
}

}  // namespace vgi
