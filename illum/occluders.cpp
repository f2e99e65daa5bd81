#include "illum/occluders.h"

#include <glad/gl.h>

#include <chrono>
#include <memory>

#include "core/error.h"
#include "core/scene.h"
#include "traverse/embree_tracer.h"

namespace vgi {

namespace {
// Mesh `m`'s simplified triangles at `time`, 3 world-space positions each (as flattenMesh transforms).
void worldCorners(const Mesh& m, const SimplifiedMesh& s, float time, std::vector<glm::vec3>& out) {
  const glm::mat4 M = m.objectToWorld(time);
  for (const glm::uvec3& t : s.triangles)
    for (int k = 0; k < 3; ++k) out.push_back(glm::vec3(M * glm::vec4(s.positions[t[k]], 1.0f)));
}
}  // namespace

NearSurfaceFactory nearSurfaceByEmbree() {
  return [](const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& tris,
            float tolerance) -> NearSurface {
    FlatScene f;
    for (const glm::uvec3& t : tris) {
      for (int k = 0; k < 3; ++k) {
        f.positions.push_back(positions[t[k]]);
        f.normals.emplace_back(0.0f, 0.0f, 1.0f);
        f.uvs.emplace_back(0.0f);
      }
      f.material.push_back(0);
      f.meshOfTriangle.push_back(0);
    }
    auto bvh = std::make_shared<EmbreeTracer>(f);
    return [bvh, tolerance](const glm::vec3& p, const glm::vec3& n) {
      return bvh->occluded(p, n, 0.0f, tolerance) || bvh->occluded(p, -n, 0.0f, tolerance);
    };
  };
}

Occluders::Occluders(const Scene& scene, size_t budget, float tolerance, float time) {
  const auto t0 = std::chrono::steady_clock::now();
  meshes_ = simplifySceneMeshes(scene, budget, tolerance, nearSurfaceByEmbree());
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::vector<glm::vec3> corners;
  long splitOff = 0;
  for (size_t i = 0; i < meshes_.size(); ++i) {
    if (meshes_[i].simplified) tolerance_ = tolerance;
    first_.push_back(triangles_);
    triangles_ += meshes_[i].triangles.size();
    splitOff += meshes_[i].facesSplitOff;
    worldCorners(scene.meshes[i], meshes_[i], time, corners);
  }
  glCreateVertexArrays(1, &vao_);
  glCreateBuffers(1, &vbo_);
  glNamedBufferStorage(vbo_, GLsizeiptr(std::max<size_t>(corners.size(), 1) * sizeof(glm::vec3)),
                       corners.empty() ? nullptr : corners.data(), GL_DYNAMIC_STORAGE_BIT);
  glVertexArrayVertexBuffer(vao_, 0, vbo_, 0, sizeof(glm::vec3));
  glEnableVertexArrayAttrib(vao_, 0);
  glVertexArrayAttribFormat(vao_, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao_, 0, 0);
  stats_ = {{"scene_triangles", scene.triangleCount()},
            {"triangles", triangles_},
            {"budget", budget},
            {"tolerance", tolerance_},
            {"faces_split_off", splitOff},
            {"simplify_ms", ms}};
}

Occluders::~Occluders() {
  glDeleteBuffers(1, &vbo_);
  glDeleteVertexArrays(1, &vao_);
}

void Occluders::setTime(const Scene& scene, float time) {
  VGI_CHECK(scene.meshes.size() == meshes_.size());
  std::vector<glm::vec3> corners;
  for (size_t i = 0; i < meshes_.size(); ++i) {
    if (!scene.meshes[i].dynamic || meshes_[i].triangles.empty()) continue;
    corners.clear();
    worldCorners(scene.meshes[i], meshes_[i], time, corners);
    glNamedBufferSubData(vbo_, GLintptr(first_[i] * 3 * sizeof(glm::vec3)),
                         GLsizeiptr(corners.size() * sizeof(glm::vec3)), corners.data());
  }
}

void Occluders::drawInstanced(int instances) const {
  glBindVertexArray(vao_);
  glDrawArraysInstanced(GL_TRIANGLES, 0, GLsizei(3 * triangles_), GLsizei(instances));
}

}  // namespace vgi
