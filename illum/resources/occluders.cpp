#include "illum/resources/occluders.h"

#include <glad/gl.h>

#include <chrono>
#include <memory>

#include "core/profiler.h"
#include "traverse/embree_tracer.h"

namespace vgi {

NearSurfaceFactory nearSurfaceByEmbree() {
  return [](const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& tris,
            float tolerance) -> NearSurface {
    Scene mesh;
    mesh.meshes.emplace_back();
    mesh.meshes[0].positions = positions;
    mesh.meshes[0].triangles = tris;
    auto bvh = std::make_shared<EmbreeTracer>(flatten(mesh));
    return [bvh, tolerance](const glm::vec3& p, const glm::vec3& n) {
      return bvh->occluded(p, n, 0.0f, tolerance) || bvh->occluded(p, -n, 0.0f, tolerance);
    };
  };
}

Occluders::Occluders(const Scene& scene, size_t budget, float tolerance, float time) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<SimplifiedMesh> meshes =
      simplifySceneMeshes(scene, budget, tolerance, nearSurfaceByEmbree());
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  long splitOff = 0;
  for (size_t i = 0; i < meshes.size(); ++i) {
    if (meshes[i].simplified) tolerance_ = tolerance;
    first_.push_back(triangles_);
    triangles_ += meshes[i].triangles.size();
    splitOff += meshes[i].facesSplitOff;
    occluders_.meshes.push_back(withGeometry(scene.meshes[i], meshes[i]));
  }
  const std::vector<glm::vec3> corners = flatten(occluders_, time).positions;
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
            // Within 10 %: a mesh's share of the budget is rounded up, and a few triangles are kept whole.
            {"budget_met", double(triangles_) <= 1.1 * double(budget)},
            {"tolerance", tolerance_},
            {"faces_split_off", splitOff},
            {"simplify_ms", ms}};
}

Occluders::~Occluders() {
  glDeleteBuffers(1, &vbo_);
  glDeleteVertexArrays(1, &vao_);
}

void Occluders::setTime(float time) {
  for (size_t i = 0; i < occluders_.meshes.size(); ++i) {
    if (!occluders_.meshes[i].dynamic || occluders_.meshes[i].triangles.empty()) continue;
    FlatScene f;
    flattenMesh(occluders_, int(i), time, f);
    glNamedBufferSubData(vbo_, GLintptr(first_[i] * 3 * sizeof(glm::vec3)),
                         GLsizeiptr(f.positions.size() * sizeof(glm::vec3)), f.positions.data());
  }
}

void Occluders::drawInstanced(int instances) const {
  glBindVertexArray(vao_);
  glDrawArraysInstanced(GL_TRIANGLES, 0, GLsizei(3 * triangles_), GLsizei(instances));
}

namespace {
class OccludersResource : public Resource {
 public:
  explicit OccludersResource(const OccluderNeed& n) : need_(n) {}
  bool update(SceneResources& res, const ResourceNeed&, Profiler& prof) override {
    auto s = prof.scope("occluders");
    if (!occ_)
      occ_ = std::make_unique<Occluders>(res.scene(), need_.triangles, need_.tolerance, res.time());
    else
      occ_->setTime(res.time());
    return true;
  }
  void* offer(const std::type_info& t) override { return offerOf(t, occ_.get()); }

 private:
  OccluderNeed need_;
  std::unique_ptr<Occluders> occ_;
};
}  // namespace

ResourceKind occludersKind() {
  return {"occluders",
          "the scene simplified within a tolerance, for passes that draw it many times for its occlusion",
          [](const ResourceNeed&) { return std::vector<ResourceNeed>{}; },
          [](const ResourceNeed& n, const SceneNeeds&, const std::string& method, bool gl) {
            requireGl(n, method, gl);
          },
          [](const ResourceNeed&) { return std::vector<std::string>{"occluders"}; },
          [](const ResourceNeed& n, SceneResources&) -> std::unique_ptr<Resource> {
            return std::make_unique<OccludersResource>(n.spec<OccluderNeed>());
          },
          ""};
}

const ResourceKind& OccluderNeed::row() {
  static const ResourceKind k = occludersKind();
  return k;
}

}  // namespace vgi
