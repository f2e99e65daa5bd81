// Atlas-based binary voxelization — Thiedemann et al., "Voxel-based Global
// Illumination", I3D 2011, §3.1: each mesh is rendered once into its texture
// atlas, writing world positions (unused texels stay invalid); then one point
// per valid texel sets the bit of its cell. §3.2: static meshes are voxelized
// once; each frame copies that grid and inserts the dynamic meshes only.
//
// Sliver triangles may cover no texel centre when filled, so the atlas is drawn
// three times — corners as points, edges as lines, then the filled triangles on
// top — and every texel written holds a point of the surface. The count of triangles left
// without any texel is reported ("triangles_without_texels").
//
// Parameters (VoxelizeRequest): texelsPerVoxel (default 2√2: texel = smallest
// voxel edge · √2/4, the rule in grid_metrics.h), atlasResolution (manual, per
// mesh), atlasCacheDir.
#include "voxelize/atlas_voxelizer.h"

#include <glad/gl.h>

#include <set>

#include "core/error.h"
#include "core/gl_context.h"
#include "core/shader_library.h"
#include "voxelize/atlas.h"
#include "voxelize/gpu_grid.h"

namespace vgi {

void insertAtlasPoints(const std::vector<glm::vec4>& positions, BinaryGrid& grid) {
  const shared::GridParams g = grid.box().params();
  for (const glm::vec4& p : positions) {
    if (p.w == 0.0f) continue;
    shared::PointBit b = shared::pointBit(g, glm::vec3(p));
    if (b.word != 0xffffffffu) grid.words()[b.word] |= b.bit;
  }
}

struct AtlasVoxelizer::MeshGpu {
  std::string name;
  bool dynamic = false;
  glm::mat4 model0{1.0f};   // object → world at time 0 (the atlas's frame)
  const Mesh* mesh = nullptr;
  std::vector<glm::vec2> uv;  // the atlas, 3 per triangle
  int resolution = 0;
  GLsizei corners = 0, lineIndices = 0;
  unsigned vao = 0, vbo = 0, ebo = 0;
};

AtlasVoxelizer::AtlasVoxelizer(const VoxelizeRequest& req, Profiler& prof,
                               std::vector<std::vector<glm::vec4>>* atlasPoints)
    : request_(req) {
  VGI_CHECK(req.gl && req.shaders);
  GLint maxTex = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTex);
  const float texel = autoTexelWorld(req.box.voxelSize(), req.texelsPerVoxel);
  renderProg_ = req.shaders->program({"voxelize/atlas_render.vert.glsl", "voxelize/atlas_render.frag.glsl"});
  insertProg_ = req.shaders->program({"voxelize/atlas_insert.comp.glsl"});
  setGridUniforms(insertProg_, req.box);
  static_ = std::make_unique<GpuGridBuffer>(req.box);
  frame_ = std::make_unique<GpuGridBuffer>(req.box);
  const uint32_t zero = 0;
  glCreateBuffers(1, &counter_);
  glNamedBufferStorage(counter_, 4, &zero, GL_DYNAMIC_STORAGE_BIT);

  nlohmann::json atlases = nlohmann::json::array();
  double atlasMs = 0;
  int staticCount = 0, dynamicCount = 0;
  for (const Mesh& mesh : req.scene->meshes) {
    auto m = std::make_unique<MeshGpu>();
    m->name = mesh.name;
    m->mesh = &mesh;
    m->dynamic = mesh.dynamic && !mesh.keyframes.empty();
    (m->dynamic ? dynamicCount : staticCount)++;
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
    // Position (RGBA32F) + triangle id (R32I) per texel; refuse before GL's allocation fails.
    const double bytes = double(atlas.resolution) * atlas.resolution * 20.0;
    if (bytes > double(1u << 31))
      fail("atlas voxelizer: mesh '", mesh.name, "' needs a ", atlas.resolution, "x", atlas.resolution, " atlas (",
           bytes / (1 << 20), " MiB of render targets, limit 2048 MiB); lower --texels-per-voxel (",
           req.texelsPerVoxel, ") or the grid resolution, or set --atlas-resolution");
    maxResolution_ = std::max(maxResolution_, atlas.resolution);
    nlohmann::json aj = atlas.toJson();
    aj["mesh"] = mesh.name;
    aj["triangles"] = mesh.triangles.size();
    aj["dynamic"] = m->dynamic;
    atlases.push_back(aj);

    std::vector<float> verts;
    verts.reserve(mesh.triangles.size() * 18);
    std::vector<uint32_t> lines;
    lines.reserve(mesh.triangles.size() * 6);
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const glm::vec3& p = mesh.positions[mesh.triangles[t][k]];
        const glm::vec2& uv = atlas.uv[3 * t + size_t(k)];
        verts.insert(verts.end(), {p.x, p.y, p.z, uv.x, uv.y, float(t)});
      }
      uint32_t b = uint32_t(3 * t);
      lines.insert(lines.end(), {b, b + 1, b + 1, b + 2, b + 2, b});
    }
    m->corners = GLsizei(3 * mesh.triangles.size());
    m->lineIndices = GLsizei(lines.size());
    glCreateVertexArrays(1, &m->vao);
    glCreateBuffers(1, &m->vbo);
    glCreateBuffers(1, &m->ebo);
    glNamedBufferStorage(m->vbo, GLsizeiptr(std::max<size_t>(verts.size(), 1) * sizeof(float)), verts.data(), 0);
    glNamedBufferStorage(m->ebo, GLsizeiptr(std::max<size_t>(lines.size(), 1) * sizeof(uint32_t)), lines.data(), 0);
    glVertexArrayVertexBuffer(m->vao, 0, m->vbo, 0, 6 * sizeof(float));
    glVertexArrayElementBuffer(m->vao, m->ebo);
    const int sizes[3] = {3, 2, 1}, offsets[3] = {0, 3, 5};
    for (unsigned a = 0; a < 3; ++a) {
      glEnableVertexArrayAttrib(m->vao, a);
      glVertexArrayAttribFormat(m->vao, a, sizes[a], GL_FLOAT, GL_FALSE, unsigned(offsets[a]) * sizeof(float));
      glVertexArrayAttribBinding(m->vao, a, 0);
    }
    meshes_.push_back(std::move(m));
  }

  // One atlas target, as large as the largest atlas; each mesh uses its corner.
  const int R = std::max(maxResolution_, 1);
  glCreateTextures(GL_TEXTURE_2D, 2, targets_);
  glTextureStorage2D(targets_[0], 1, GL_RGBA32F, R, R);
  glTextureStorage2D(targets_[1], 1, GL_R32I, R, R);
  glCreateFramebuffers(1, &fbo_);
  glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, targets_[0], 0);
  glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT1, targets_[1], 0);
  const GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(fbo_, 2, bufs);
  if (glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    fail("atlas voxelizer: the ", R, "x", R, " atlas framebuffer is incomplete on ", req.gl->renderer());

  // Static meshes into the static grid, once; every mesh's texel coverage is measured here.
  long lost = 0, sharedTotal = 0;
  for (size_t i = 0; i < meshes_.size(); ++i) {
    const MeshGpu& m = *meshes_[i];
    std::vector<int> ids;
    std::vector<glm::vec4>* points = nullptr;
    if (atlasPoints) {
      atlasPoints->emplace_back();
      points = &atlasPoints->back();
    }
    // Dynamic meshes are only measured here (into the frame grid, which each frame overwrites).
    uint32_t n = renderAndInsert(m, m.dynamic ? req.time : 0.0f, m.dynamic ? *frame_ : *static_, prof, &ids, points);
    if (!m.dynamic) staticPoints_ += n;
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
      for (int y = std::max(0, int(std::floor(lo.y - 0.5f))); !near && y <= std::min(R - 1, int(hi.y + 0.5f)); ++y)
        for (int x = std::max(0, int(std::floor(lo.x - 0.5f))); !near && x <= std::min(R - 1, int(hi.x + 0.5f)); ++x)
          near = ids[size_t(y) * size_t(R) + size_t(x)] >= 0;
      (near ? sharing : meshLost)++;
    }
    atlases[i]["triangles_without_texels"] = meshLost;
    atlases[i]["triangles_sampled_by_neighbours"] = sharing;
    lost += meshLost;
    sharedTotal += sharing;
  }
  stats_["atlas_resolution"] = maxResolution_;
  stats_["atlases"] = atlases;
  stats_["atlas_build_ms"] = atlasMs;
  stats_["texel_world"] = texel;
  stats_["texels_per_voxel"] = req.texelsPerVoxel;
  stats_["triangles_without_texels"] = lost;
  stats_["triangles_sampled_by_neighbours"] = sharedTotal;
  stats_["static_meshes"] = staticCount;
  stats_["dynamic_meshes"] = dynamicCount;
}

AtlasVoxelizer::~AtlasVoxelizer() {
  for (auto& m : meshes_) {
    unsigned b[2] = {m->vbo, m->ebo};
    glDeleteBuffers(2, b);
    glDeleteVertexArrays(1, &m->vao);
  }
  glDeleteFramebuffers(1, &fbo_);
  glDeleteTextures(2, targets_);
  glDeleteBuffers(1, &counter_);
}

uint32_t AtlasVoxelizer::renderAndInsert(const MeshGpu& m, float time, const GpuGridBuffer& target, Profiler& prof,
                                         std::vector<int>* ids, std::vector<glm::vec4>* points) {
  const int R = m.resolution;
  const uint32_t zero = 0;
  glNamedBufferSubData(counter_, 0, 4, &zero);
  {
    auto s = prof.scope("atlas_render");
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glViewport(0, 0, R, R);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    const float clearPos[4] = {0, 0, 0, 0};
    const int clearId[4] = {-1, -1, -1, -1};
    glClearBufferfv(GL_COLOR, 0, clearPos);
    glClearBufferiv(GL_COLOR, 1, clearId);
    glUseProgram(renderProg_);
    glm::mat4 model = m.mesh->objectToWorld(time);
    glUniformMatrix4fv(glGetUniformLocation(renderProg_, "uModel"), 1, GL_FALSE, &model[0][0]);
    glBindVertexArray(m.vao);
    // Corners and edges first, the fill last: a texel whose centre a triangle
    // covers keeps that centre's point (the regular lattice the resolution
    // rule relies on); the others hold edge or corner points of slivers.
    const int clampLoc = glGetUniformLocation(renderProg_, "uClampToTriangle");
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, m.vbo);
    glUniform1i(clampLoc, 0);
    glDrawArrays(GL_POINTS, 0, m.corners);
    glUniform1i(clampLoc, 1);  // line fragments overshoot the edge's ends
    glDrawElements(GL_LINES, m.lineIndices, GL_UNSIGNED_INT, nullptr);
    glUniform1i(clampLoc, 0);
    glDrawArrays(GL_TRIANGLES, 0, m.corners);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }
  {
    auto s = prof.scope("insertion");
    glUseProgram(insertProg_);
    glProgramUniform2i(insertProg_, glGetUniformLocation(insertProg_, "uAtlasSize"), R, R);
    glBindTextureUnit(0, targets_[0]);
    target.bind(0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, counter_);
    glDispatchCompute(unsigned(R + 7) / 8, unsigned(R + 7) / 8, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  }
  if (ids) {
    ids->assign(size_t(R) * size_t(R), -1);
    glGetTextureSubImage(targets_[1], 0, 0, 0, 0, R, R, 1, GL_RED_INTEGER, GL_INT, GLsizei(ids->size() * sizeof(int)),
                         ids->data());
  }
  if (points) {
    points->assign(size_t(R) * size_t(R), glm::vec4(0.0f));
    glGetTextureSubImage(targets_[0], 0, 0, 0, 0, R, R, 1, GL_RGBA, GL_FLOAT,
                         GLsizei(points->size() * sizeof(glm::vec4)), points->data());
  }
  uint32_t n = 0;
  glGetNamedBufferSubData(counter_, 0, 4, &n);
  return n;
}

void AtlasVoxelizer::voxelizeFrame(float time, Profiler& prof) {
  {
    auto s = prof.scope("copy");
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    glCopyNamedBufferSubData(static_->buffer(), frame_->buffer(), 0, 0, GLsizeiptr(static_->bytes()));
  }
  framePoints_ = staticPoints_;
  for (auto& m : meshes_)
    if (m->dynamic) framePoints_ += renderAndInsert(*m, time, *frame_, prof, nullptr, nullptr);
}

BinaryGrid AtlasVoxelizer::readFrame() const {
  BinaryGrid grid(request_.box);
  frame_->read(grid);
  return grid;
}

nlohmann::json AtlasVoxelizer::stats() const {
  nlohmann::json s = stats_;
  s["points"] = framePoints_;
  return s;
}

BinaryGrid voxelizeAtlasGl(const VoxelizeRequest& req, Profiler& prof, nlohmann::json& stats,
                           std::vector<std::vector<glm::vec4>>* atlasPoints) {
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
