// Occluder simplification (voxelize/mesh_simplify.h, illum/occluders.h): the
// two-sided tolerance on a sphere, the locked outline of an open sheet, a scene
// within its budget drawn as it is, and the property `avg`'s VPL shadow maps
// rely on — point pairs that see each other in Sibenik still do through the
// simplified scene, with the shadow test's tolerance bias.
#include "voxelize/mesh_simplify.h"

#include <glad/gl.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <random>

#include "core/gl_context.h"
#include "core/scene.h"
#include "core/scene_loader.h"
#include "illum/resources/occluders.h"
#include "shaders/shared/vpl.glsl"
#include "test_util.h"
#include "traverse/embree_tracer.h"

namespace vgi {
namespace {

// The simplified meshes as a scene of their own (each with its original's transform), for Embree.
FlatScene flatOf(const std::vector<SimplifiedMesh>& simplified, const Scene& original = Scene()) {
  Scene s;
  for (size_t i = 0; i < simplified.size(); ++i)
    s.meshes.push_back(withGeometry(i < original.meshes.size() ? original.meshes[i] : Mesh(), simplified[i]));
  return flatten(s);
}

// A unit sphere, rows × columns quads split in two, outward-facing.
void unitSphere(int rows, int cols, std::vector<glm::vec3>& pos, std::vector<glm::uvec3>& tri) {
  for (int i = 0; i <= rows; ++i)
    for (int j = 0; j < cols; ++j) {
      const float th = float(M_PI) * float(i) / float(rows), ph = 2.0f * float(M_PI) * float(j) / float(cols);
      pos.emplace_back(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
    }
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) {
      const uint32_t a = i * cols + j, b = i * cols + (j + 1) % cols, c = (i + 1) * cols + j,
                     d = (i + 1) * cols + (j + 1) % cols;
      if (i > 0) tri.emplace_back(a, b, c);  // (the poles' rows: one vertex, welded)
      if (i < rows - 1) tri.emplace_back(b, d, c);
    }
}

double area(const std::vector<glm::vec3>& p, const std::vector<glm::uvec3>& tris) {
  double a = 0;
  for (const glm::uvec3& t : tris)
    a += 0.5 * double(glm::length(glm::cross(p[t.y] - p[t.x], p[t.z] - p[t.x])));
  return a;
}

}  // namespace

// A finely tessellated sphere (39 600 triangles) simplified at tolerance 1e-3
// of its radius: far fewer triangles, every face facing out, and within the
// tolerance both ways — the new faces' centroids near the sphere (the ray test
// has the tessellation's own sagitta, 1.2e-4, on top) and the original
// vertices near the new faces (ModHausdorff).
TEST(MeshSimplify, ASphereStaysWithinTheToleranceBothWays) {
  std::vector<glm::vec3> pos;
  std::vector<glm::uvec3> tri;
  unitSphere(100, 200, pos, tri);
  const float tol = 1e-3f;
  const SimplifiedMesh s = simplifyMesh(pos, tri, 500, tol, nearSurfaceByEmbree()(pos, tri, tol));
  EXPECT_TRUE(s.simplified);
  EXPECT_EQ(s.facesSplitOff, 0);
  EXPECT_LT(s.triangles.size(), tri.size() / 5);
  EXPECT_GE(s.triangles.size(), 500u);
  float centroidIn = 0, vertexOff = 0;
  int inward = 0;
  for (const glm::uvec3& t : s.triangles) {
    const glm::vec3 a = s.positions[t.x], b = s.positions[t.y], c = s.positions[t.z];
    const glm::vec3 centroid = (a + b + c) / 3.0f;
    centroidIn = std::max(centroidIn, std::abs(1.0f - glm::length(centroid)));
    inward += glm::dot(glm::cross(b - a, c - a), centroid) <= 0.0f;
  }
  for (const glm::vec3& p : s.positions) vertexOff = std::max(vertexOff, std::abs(glm::length(p) - 1.0f));
  std::printf("sphere %zu -> %zu triangles: centroids off by up to %g, vertices %g (tolerance %g)\n",
              tri.size(), s.triangles.size(), centroidIn, vertexOff, tol);
  EXPECT_EQ(inward, 0) << "ModNormalFlipping";
  EXPECT_LT(centroidIn, tol + 3e-4f) << "the new faces near the original surface (measured 1.2e-3)";
  EXPECT_LT(vertexOff, tol + 3e-4f);
  // The other way: each original vertex within the tolerance of the new faces, radially.
  EmbreeTracer simplified(flatOf({s}));
  int far = 0;
  for (const glm::vec3& p : pos) {
    const glm::vec3 n = glm::normalize(p);
    const TriangleHit in = simplified.firstHit(p + 2.0f * tol * n, -n, 0.0f, 4.0f * tol);
    far += !in.hit || std::abs(in.t - 2.0f * tol) > 1.5f * tol;  // radial, not closest-point
  }
  EXPECT_EQ(far, 0) << "original vertices farther than the tolerance from the simplified sphere";
}

// A flat open sheet of 50 × 50 quads simplified to 8 triangles: its outline stays where it was —
// the four corners kept, every vertex left on the outline still on it, the area whole — while the
// interior collapses and then (the outline pass) the straight edges' inner vertices go.
TEST(MeshSimplify, AnOpenSheetKeepsItsOutline) {
  std::vector<glm::vec3> pos;
  std::vector<glm::uvec3> tri;
  const int n = 50;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) pos.emplace_back(float(i) / n, 0.0f, float(j) / n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const uint32_t a = i * (n + 1) + j, b = a + 1, c = a + n + 1, d = c + 1;
      tri.emplace_back(a, b, c);
      tri.emplace_back(b, d, c);
    }
  const SimplifiedMesh s = simplifyMesh(pos, tri, 8, 1e-3f, nearSurfaceByEmbree()(pos, tri, 1e-3f));
  EXPECT_TRUE(s.simplified);
  EXPECT_LE(s.triangles.size(), 8u);  // the budget holds: the outline's 196 inner vertices went too
  EXPECT_NEAR(area(s.positions, s.triangles), 1.0, 1e-5);
  for (const glm::vec3& corner :
       {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 0, 1), glm::vec3(1, 0, 1)})
    EXPECT_EQ(std::count(s.positions.begin(), s.positions.end(), corner), 1) << corner.x << " " << corner.z;
  for (const glm::vec3& p : s.positions)
    EXPECT_TRUE(p.x == 0 || p.x == 1 || p.z == 0 || p.z == 1) << p.x << " " << p.z;
  for (const glm::vec3& p : s.positions) EXPECT_EQ(p.y, 0.0f);
}

// The built-in Cornell box (30 triangles) is within any budget it is given:
// each mesh comes back as its own triangles, in order — the same geometry.
TEST(MeshSimplify, ASceneWithinTheBudgetIsDrawnAsItIs) {
  const Scene scene = loadScene("builtin:cornell");
  for (size_t budget : {size_t(8192), size_t(1)}) {  // 1: every mesh is at most kKeptTriangles
    const std::vector<SimplifiedMesh> s = simplifySceneMeshes(scene, budget, 1e-3f, nearSurfaceByEmbree());
    ASSERT_EQ(s.size(), scene.meshes.size());
    for (size_t i = 0; i < s.size(); ++i) {
      EXPECT_FALSE(s[i].simplified);
      EXPECT_EQ(s[i].positions, scene.meshes[i].positions);
      EXPECT_EQ(s[i].triangles, scene.meshes[i].triangles);
    }
  }
}

// A dynamic mesh's simplified triangles follow the scene's animation:
// uploaded at time 0 and moved to time 1 (setTime), the buffer holds what an
// upload at time 1 holds; the static box stays. The box alone is within the
// budget, so it is drawn as it is and the tolerance is 0.
TEST(Occluders, DynamicMeshesMoveWithTheScene) {
  std::unique_ptr<GlContext> gl = GlContext::create();
  Scene scene = loadScene("builtin:cornell");
  const size_t boxTriangles = scene.triangleCount();
  {
    Occluders box(scene, 1000, 1e-3f, 0.0f);
    EXPECT_EQ(box.triangleCount(), boxTriangles);
    EXPECT_EQ(box.tolerance(), 0.0f);
  }
  Mesh sphere;
  sphere.name = "sphere";
  unitSphere(40, 80, sphere.positions, sphere.triangles);
  sphere.transform = glm::scale(glm::mat4(1.0f), glm::vec3(0.1f));
  sphere.dynamic = true;
  Keyframe k0, k1;
  k0.translation = glm::vec3(0.2f, 0.1f, 0.2f);
  k1.time = 1.0f;
  k1.translation = glm::vec3(0.35f, 0.3f, 0.25f);
  k1.rotation = glm::angleAxis(1.0f, glm::normalize(glm::vec3(1, 2, 0)));
  sphere.keyframes = {k0, k1};
  scene.meshes.push_back(sphere);
  auto corners = [](const Occluders& o) {
    std::vector<glm::vec3> c(3 * o.triangleCount());
    glGetNamedBufferSubData(o.vertexBuffer(), 0, GLsizeiptr(c.size() * sizeof(glm::vec3)), c.data());
    return c;
  };
  const float tol = 1e-3f;
  Occluders moved(scene, 1000, tol, 0.0f);
  const std::vector<glm::vec3> atZero = corners(moved);
  moved.setTime(1.0f);
  const Occluders atOne(scene, 1000, tol, 1.0f);
  EXPECT_EQ(moved.tolerance(), tol);
  EXPECT_LT(moved.triangleCount(), scene.triangleCount() / 2);
  EXPECT_EQ(moved.triangleCount(), atOne.triangleCount());
  const std::vector<glm::vec3> c = corners(moved);
  EXPECT_EQ(c, corners(atOne));
  EXPECT_NE(c, atZero);
  // The world-space tolerance holds for the sphere scaled to radius 0.1 (simplified in object space).
  const glm::vec3 centre = glm::vec3(scene.meshes.back().objectToWorld(0.0f) * glm::vec4(0, 0, 0, 1));
  float off = 0.0f;
  for (size_t i = 3 * boxTriangles; i < atZero.size(); ++i)
    off = std::max(off, std::abs(glm::length(atZero[i] - centre) - 0.1f));
  std::printf("dynamic sphere %zu -> %zu triangles, %g off the radius\n",
              scene.meshes.back().triangles.size(), moved.triangleCount() - boxTriangles, off);
  EXPECT_LT(off, tol + 2e-4f);
  EXPECT_TRUE(std::equal(c.begin(), c.begin() + 3 * long(boxTriangles), atZero.begin()))
      << "the box is static";
  EXPECT_EQ(gl->errorCount(), 0);
}

// Sibenik (75 000 triangles) at avg's defaults (8192, 0.002 × diagonal): pairs
// of surface points that see each other in the scene — the first lifted off
// its surface as avg lifts its VPLs (0.015 × diagonal, one AVG cell at 64³) —
// are tested through the simplified scene with the gather's bias (the
// tolerance over the receiver's cosine, ≥ 0.2). Measured: 1.8 % of them
// blocked (1.7 % with every outline locked); with ModHausdorff alone (no test
// of the new faces against the original surface) 47 %, which is why the
// two-sided test is there. Pairs the scene hides: 12.8 % seen through the
// simplified scene, 10.9 % through the scene itself with the same slack.
TEST(MeshSimplify, SibenikPairsThatSeeEachOtherStillDo) {
  if (test::sharedScene("sibenik/sibenik.obj").empty()) GTEST_SKIP() << "../shared/scenes not present";
  const Scene scene = loadScene(std::string(VGI_TEST_DATA) + "/../../scenes/sibenik.json");
  const float diag = scene.bounds().diagonal(), tolerance = 0.002f * diag;
  const FlatScene orig = flatten(scene);
  const EmbreeTracer exact(orig);
  auto blockedFraction = [&](const std::vector<SimplifiedMesh>& s, size_t& triangles, double& leaked) {
    triangles = 0;
    for (const SimplifiedMesh& m : s) triangles += m.triangles.size();
    const EmbreeTracer simplified(flatOf(s, scene));
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    auto surfacePoint = [&](glm::vec3& p, glm::vec3& n) {
      const size_t t = size_t(u(rng) * float(orig.triangleCount())) % orig.triangleCount();
      float r1 = u(rng), r2 = u(rng);
      if (r1 + r2 > 1) r1 = 1 - r1, r2 = 1 - r2;
      const glm::vec3 p0 = orig.positions[3 * t], p1 = orig.positions[3 * t + 1],
                      p2 = orig.positions[3 * t + 2];
      const glm::vec3 c = glm::cross(p1 - p0, p2 - p0);
      p = p0 + r1 * (p1 - p0) + r2 * (p2 - p0);
      n = glm::length(c) > 0 ? glm::normalize(c) : glm::vec3(0.0f);
    };
    const float eps = 1e-4f * diag, lift = 0.015f * diag;
    int visible = 0, blocked = 0, hidden = 0, seenThrough = 0;
    for (int i = 0; i < 60000; ++i) {
      glm::vec3 p0, n, q, m;
      surfacePoint(p0, n);
      surfacePoint(q, m);
      const glm::vec3 p = p0 + lift * n;
      glm::vec3 d = q - p;
      const float len = glm::length(d);
      if (!(len > 1e-3f * diag)) continue;
      d /= len;
      if (!(glm::dot(d, n) > 0) || !(glm::dot(-d, m) > 0)) continue;  // the surfaces' front sides face
      if (exact.occluded(p0, n, eps, lift)) continue;                 // lifted into something
      const float bias =
          shared::vplShadowSlack(0.0f, 0.0f, len, tolerance, glm::dot(-d, m)) + eps;  // the gather's
      if (exact.occluded(p, d, eps, len - eps)) {  // hidden: does the simplified scene let it through?
        ++hidden;
        seenThrough += !simplified.occluded(p, d, eps, len - bias);
        continue;
      }
      ++visible;
      blocked += simplified.occluded(p, d, eps, len - bias);
    }
    EXPECT_GT(visible, 2000);
    EXPECT_GT(hidden, 2000);
    leaked = double(seenThrough) / double(hidden);
    return double(blocked) / double(visible);
  };
  size_t twoSided = 0, oneSided = 0;
  double leakTwoSided = 0, leakOneSided = 0;
  const double withTest = blockedFraction(simplifySceneMeshes(scene, 8192, tolerance, nearSurfaceByEmbree()),
                                          twoSided, leakTwoSided);
  const double without =
      blockedFraction(simplifySceneMeshes(scene, 8192, tolerance, {}), oneSided, leakOneSided);
  // The same test through the scene itself: what the gather's slack alone lets through.
  size_t all = 0;
  double leakScene = 0;
  blockedFraction(simplifySceneMeshes(scene, scene.triangleCount(), tolerance, {}), all, leakScene);
  std::printf("the scene itself: %.4f of hidden pairs seen\n", leakScene);
  std::printf(
      "Sibenik %zu triangles: two-sided %zu (%.4f of visible pairs blocked, %.4f of hidden ones seen), "
      "one-sided %zu (%.4f, %.4f)\n",
      scene.triangleCount(), twoSided, withTest, leakTwoSided, oneSided, without, leakOneSided);
  EXPECT_LT(twoSided, scene.triangleCount() / 3);
  EXPECT_LT(withTest, 0.03);
  // The outlines may move by the tolerance, no more: measured 0.1283 of the hidden pairs seen through
  // the simplified scene against 0.1087 through the scene itself with the gather's slack (0.1228 with
  // every outline locked, at 27 904 triangles instead of 22 461).
  EXPECT_LT(leakTwoSided, leakScene + 0.03);
  EXPECT_GT(without, 5 * withTest) << "the test of the new faces is what keeps the pairs visible";
}

}  // namespace vgi
