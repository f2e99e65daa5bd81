// Atlas-based binary voxelization — Thiedemann et al., "Voxel-based Global
// Illumination", I3D 2011, §3.1: each mesh is rendered once into its texture
// atlas, writing world positions (unused texels stay invalid); then one point
// per valid texel sets the bit of its cell. Static and dynamic meshes alike are
// rendered at the request's time.
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

BinaryGrid voxelizeAtlasGl(const VoxelizeRequest& req, Profiler& prof, nlohmann::json& stats,
                           std::vector<std::vector<glm::vec4>>* atlasPoints) {
  VGI_CHECK(req.gl && req.shaders);
  const Scene& scene = *req.scene;
  BinaryGrid grid(req.box);
  GLint maxTex = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTex);
  const float texel = autoTexelWorld(req.box.voxelSize(), req.texelsPerVoxel);

  unsigned renderProg = req.shaders->program({"voxelize/atlas_render.vert.glsl", "voxelize/atlas_render.frag.glsl"});
  unsigned insertProg = req.shaders->program({"voxelize/atlas_insert.comp.glsl"});

  GpuGridBuffer target(req.box);
  unsigned counterBuf = 0;
  const uint32_t zero = 0;
  glCreateBuffers(1, &counterBuf);
  glNamedBufferStorage(counterBuf, 4, &zero, GL_DYNAMIC_STORAGE_BIT);
  setGridUniforms(insertProg, req.box);

  nlohmann::json atlases = nlohmann::json::array();
  int largest = 0;
  long lost = 0;
  double atlasMs = 0;
  for (const Mesh& mesh : scene.meshes) {
    // The atlas comes from the mesh at time 0 (rigid motion keeps lengths, so a
    // dynamic mesh keeps its cached atlas); the positions rendered are at `time`.
    std::vector<glm::vec3> p0(mesh.positions.size()), pt(mesh.positions.size());
    glm::mat4 M0 = mesh.objectToWorld(0.0f), Mt = mesh.objectToWorld(req.time);
    for (size_t i = 0; i < p0.size(); ++i) {
      p0[i] = glm::vec3(M0 * glm::vec4(mesh.positions[i], 1.0f));
      pt[i] = glm::vec3(Mt * glm::vec4(mesh.positions[i], 1.0f));
    }
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
    nlohmann::json aj = atlas.toJson();
    aj["mesh"] = mesh.name;
    aj["triangles"] = mesh.triangles.size();
    const int R = atlas.resolution;
    largest = std::max(largest, R);
    // Position (RGBA32F) + triangle id (R32I) per texel; refuse before the GL allocation fails.
    const double atlasBytes = double(R) * R * 20.0;
    if (atlasBytes > double(1u << 31))
      fail("atlas voxelizer: mesh '", mesh.name, "' needs a ", R, "x", R, " atlas (", atlasBytes / (1 << 20),
           " MiB of render targets, limit 2048 MiB); lower --texels-per-voxel (", req.texelsPerVoxel,
           ") or the grid resolution, or set --atlas-resolution");

    std::vector<float> verts;
    verts.reserve(mesh.triangles.size() * 18);
    std::vector<uint32_t> lines;
    lines.reserve(mesh.triangles.size() * 6);
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const glm::vec3& p = pt[mesh.triangles[t][k]];
        const glm::vec2& uv = atlas.uv[3 * t + size_t(k)];
        verts.insert(verts.end(), {p.x, p.y, p.z, uv.x, uv.y, float(t)});
      }
      uint32_t b = uint32_t(3 * t);
      lines.insert(lines.end(), {b, b + 1, b + 1, b + 2, b + 2, b});
    }
    unsigned vao = 0, vbo = 0, ebo = 0, fbo = 0, tex[2] = {0, 0};
    glCreateVertexArrays(1, &vao);
    glCreateBuffers(1, &vbo);
    glCreateBuffers(1, &ebo);
    glNamedBufferStorage(vbo, GLsizeiptr(verts.size() * sizeof(float)), verts.data(), 0);
    glNamedBufferStorage(ebo, GLsizeiptr(lines.size() * sizeof(uint32_t)), lines.data(), 0);
    glVertexArrayVertexBuffer(vao, 0, vbo, 0, 6 * sizeof(float));
    glVertexArrayElementBuffer(vao, ebo);
    const int sizes[3] = {3, 2, 1}, offsets[3] = {0, 3, 5};
    for (unsigned a = 0; a < 3; ++a) {
      glEnableVertexArrayAttrib(vao, a);
      glVertexArrayAttribFormat(vao, a, sizes[a], GL_FLOAT, GL_FALSE, unsigned(offsets[a]) * sizeof(float));
      glVertexArrayAttribBinding(vao, a, 0);
    }
    glCreateTextures(GL_TEXTURE_2D, 2, tex);
    glTextureStorage2D(tex[0], 1, GL_RGBA32F, R, R);
    glTextureStorage2D(tex[1], 1, GL_R32I, R, R);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex[0], 0);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT1, tex[1], 0);
    const GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(fbo, 2, bufs);
    if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      fail("atlas voxelizer: the atlas framebuffer (", R, "x", R, ") is incomplete on ", req.gl->renderer());
    {
      auto s = prof.scope("atlas_render");
      glBindFramebuffer(GL_FRAMEBUFFER, fbo);
      glViewport(0, 0, R, R);
      glDisable(GL_DEPTH_TEST);
      glDisable(GL_CULL_FACE);
      const float clearPos[4] = {0, 0, 0, 0};
      const int clearId[4] = {-1, -1, -1, -1};
      glClearBufferfv(GL_COLOR, 0, clearPos);
      glClearBufferiv(GL_COLOR, 1, clearId);
      glUseProgram(renderProg);
      glBindVertexArray(vao);
      const GLsizei corners = GLsizei(3 * mesh.triangles.size());
      // Corners and edges first, the fill last: a texel whose centre a triangle
      // covers keeps that centre's point (the regular lattice the resolution
      // rule relies on); the others hold edge or corner points of slivers.
      glDrawArrays(GL_POINTS, 0, corners);
      glDrawElements(GL_LINES, GLsizei(lines.size()), GL_UNSIGNED_INT, nullptr);
      glDrawArrays(GL_TRIANGLES, 0, corners);
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    {
      auto s = prof.scope("insertion");
      glUseProgram(insertProg);
      glProgramUniform2i(insertProg, glGetUniformLocation(insertProg, "uAtlasSize"), R, R);
      glBindTextureUnit(0, tex[0]);
      target.bind(0);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, counterBuf);
      glDispatchCompute(unsigned(R + 7) / 8, unsigned(R + 7) / 8, 1);
      glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    }
    {
      // Triangles that own no texel at all (measured, not assumed).
      std::vector<int> ids(size_t(R) * size_t(R));
      glGetTextureImage(tex[1], 0, GL_RED_INTEGER, GL_INT, GLsizei(ids.size() * sizeof(int)), ids.data());
      std::vector<char> seen(mesh.triangles.size(), 0);
      for (int id : ids)
        if (id >= 0 && size_t(id) < seen.size()) seen[size_t(id)] = 1;
      long meshLost = 0;
      for (char c : seen) meshLost += !c;
      aj["triangles_without_texels"] = meshLost;
      lost += meshLost;
      if (atlasPoints) {
        atlasPoints->emplace_back(size_t(R) * size_t(R));
        glGetTextureImage(tex[0], 0, GL_RGBA, GL_FLOAT, GLsizei(atlasPoints->back().size() * sizeof(glm::vec4)),
                          atlasPoints->back().data());
      }
    }
    atlases.push_back(aj);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(2, tex);
    unsigned bufsToDelete[2] = {vbo, ebo};
    glDeleteBuffers(2, bufsToDelete);
    glDeleteVertexArrays(1, &vao);
  }
  uint32_t points = 0;
  {
    auto s = prof.scope("readback");
    target.read(grid);
    glGetNamedBufferSubData(counterBuf, 0, 4, &points);
  }
  glDeleteBuffers(1, &counterBuf);
  stats["points"] = points;
  stats["atlas_resolution"] = largest;
  stats["atlases"] = atlases;
  stats["atlas_build_ms"] = atlasMs;
  stats["texel_world"] = texel;
  stats["texels_per_voxel"] = req.texelsPerVoxel;
  stats["triangles_without_texels"] = lost;
  return grid;
}

}  // namespace vgi
