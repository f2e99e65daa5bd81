// Generated normals (core/smooth_normals.h): the rule assimp's GenSmoothNormals applied, in linear
// time on coincident geometry (issue 33, class 10).
#include "core/smooth_normals.h"

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cmath>
#include <fstream>

#include "core/scene_loader.h"
#include "test_util.h"

namespace vgi {
namespace {

glm::vec3 faceNormal(const std::vector<glm::vec3>& p, glm::uvec3 t) {
  return glm::normalize(glm::cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]));
}

// An OBJ without normals: a UV sphere (neighbours < 60 deg apart: smooth), a cube (90 deg: flat) and an
// octagonal prism (45 deg between sides: smooth around, flat against the caps).
std::string writeShapesObj(const std::string& path) {
  std::ofstream f(path);
  int base = 1;
  auto quad = [&](int a, int b, int c, int d) {
    f << "f " << base + a << ' ' << base + b << ' ' << base + c << "\nf " << base + a << ' ' << base + c
      << ' ' << base + d << '\n';
  };
  const int nu = 24, nv = 12;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) {
      double th = M_PI * j / nv, ph = 2 * M_PI * i / nu;
      f << "v " << std::sin(th) * std::cos(ph) << ' ' << std::cos(th) << ' ' << std::sin(th) * std::sin(ph)
        << '\n';
    }
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i)
      if (j == 0 || j == nv - 1)  // a triangle at the poles
        f << "f " << base + j * (nu + 1) + i << ' ' << base + (j + 1) * (nu + 1) + (j == 0 ? i + 1 : i) << ' '
          << base + (j == 0 ? (j + 1) * (nu + 1) + i : j * (nu + 1) + i + 1) << '\n';
      else
        quad(j * (nu + 1) + i, (j + 1) * (nu + 1) + i, (j + 1) * (nu + 1) + i + 1, j * (nu + 1) + i + 1);
  base += (nu + 1) * (nv + 1);
  for (int k = 0; k < 8; ++k) f << "v " << 3 + (k & 1) << ' ' << ((k >> 1) & 1) << ' ' << (k >> 2) << '\n';
  quad(0, 2, 3, 1), quad(4, 5, 7, 6), quad(0, 1, 5, 4), quad(2, 6, 7, 3), quad(0, 4, 6, 2), quad(1, 3, 7, 5);
  base += 8;
  for (int k = 0; k < 8; ++k)
    for (int h = 0; h < 2; ++h)
      f << "v " << 6 + std::cos(k * M_PI / 4) << ' ' << h << ' ' << std::sin(k * M_PI / 4) << '\n';
  for (int k = 0; k < 8; ++k) quad(2 * k, 2 * ((k + 1) % 8), 2 * ((k + 1) % 8) + 1, 2 * k + 1);
  for (int k = 1; k < 7; ++k) {
    f << "f " << base << ' ' << base + 2 * k << ' ' << base + 2 * (k + 1) << '\n';
    f << "f " << base + 1 << ' ' << base + 2 * (k + 1) + 1 << ' ' << base + 2 * k + 1 << '\n';
  }
  return path;
}

}  // namespace

// Corner for corner against assimp's step on the same triangulated (unjoined) meshes; returns how many
// corners were smoothed (differ from their face normal). Only where assimp's importer gives each
// triangle its own corners (an OBJ of triangles): where triangles share a vertex (a triangulated quad,
// an indexed mesh) assimp counted one of their normals, the last written, and this rule counts all.
int expectAssimpsNormals(const std::string& path) {
  Assimp::Importer importer;
  importer.SetPropertyFloat(AI_CONFIG_PP_GSN_MAX_SMOOTHING_ANGLE, 60.0f);
  const aiScene* ai = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_GenSmoothNormals);
  EXPECT_TRUE(ai) << path;
  int smoothed = 0, bad = 0;
  for (unsigned mi = 0; ai && mi < ai->mNumMeshes; ++mi) {
    const aiMesh* am = ai->mMeshes[mi];
    EXPECT_TRUE(am->mNormals) << path;
    if (!am->mNormals) continue;
    std::vector<glm::vec3> p(am->mNumVertices);
    for (unsigned v = 0; v < am->mNumVertices; ++v)
      p[v] = {am->mVertices[v].x, am->mVertices[v].y, am->mVertices[v].z};
    std::vector<glm::uvec3> tris;
    for (unsigned f = 0; f < am->mNumFaces; ++f)
      if (am->mFaces[f].mNumIndices == 3)
        tris.push_back({am->mFaces[f].mIndices[0], am->mFaces[f].mIndices[1], am->mFaces[f].mIndices[2]});
    SmoothNormals sn = smoothCornerNormals(p, tris, 60.0f, 1024);
    EXPECT_EQ(sn.flatPositions, 0) << path;
    for (size_t t = 0; t < tris.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        const aiVector3D& a = am->mNormals[tris[t][k]];
        const glm::vec3 mine = sn.normals[t * 3 + k];
        if (!(glm::dot(mine, glm::vec3(a.x, a.y, a.z)) > 1.0f - 1e-6f) && bad++ < 5)
          ADD_FAILURE() << path << " mesh " << mi << " triangle " << t << " corner " << k << ": (" << mine.x
                        << ", " << mine.y << ", " << mine.z << ") vs assimp's (" << a.x << ", " << a.y << ", "
                        << a.z << ")";
        smoothed += glm::dot(mine, faceNormal(p, tris[t])) < 1.0f - 1e-4f;
      }
  }
  EXPECT_EQ(bad, 0) << path;
  return smoothed;
}

TEST(SmoothNormals, MatchAssimpsGenSmoothNormalsCornerForCorner) {
  const std::string path = writeShapesObj(testing::TempDir() + "shapes_without_normals.obj");
  Assimp::Importer importer;
  const aiScene* ai = importer.ReadFile(path, aiProcess_Triangulate);
  ASSERT_TRUE(ai && ai->mNumMeshes == 1);
  const int corners = int(ai->mMeshes[0]->mNumFaces) * 3;
  // Both kinds occur: the sphere and the prism's sides smooth; the cube (12 triangles) and the prism's
  // caps (2 x 6) keep their face normals.
  EXPECT_EQ(corners - expectAssimpsNormals(path), (12 + 12) * 3);
}

TEST(SmoothNormals, CopiesOfOneTriangleAreLinearAndKeepTheirNormal) {
  // 3e5 coincident corners at each of three positions: assimp's spatial sort took 2 s for 1e4 copies and
  // grew quadratically; here one normal cluster per position.
  std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  std::vector<glm::uvec3> tris(300000, glm::uvec3(0, 1, 2));
  SmoothNormals sn = smoothCornerNormals(p, tris, 60.0f, 1024);
  ASSERT_EQ(sn.normals.size(), tris.size() * 3);
  for (const glm::vec3& n : sn.normals) ASSERT_EQ(n, glm::vec3(0, 0, 1));
}

TEST(SmoothNormals, ACreaseSmoothsBelowTheAngleOnly) {
  // Two triangles on the edge x = 0, folded by `deg` degrees: the corners on the edge average the two
  // face normals below 60 degrees and keep their own above.
  for (float deg : {30.0f, 59.0f, 61.0f, 120.0f}) {
    const float a = glm::radians(deg);
    std::vector<glm::vec3> p = {{0, 0, 0}, {0, 0, 1}, {-1, 0, 0.5f}, {std::cos(a), std::sin(a), 0.5f}};
    std::vector<glm::uvec3> tris = {{0, 1, 2}, {1, 0, 3}};
    SmoothNormals sn = smoothCornerNormals(p, tris, 60.0f, 1024);
    const glm::vec3 n0 = faceNormal(p, tris[0]), n1 = faceNormal(p, tris[1]);
    const glm::vec3 edge = deg < 60.0f ? glm::normalize(n0 + n1) : n0;
    SCOPED_TRACE(deg);
    EXPECT_NEAR(glm::dot(sn.normals[0], edge), 1.0f, 1e-6f);  // triangle 0, corner on the edge
    EXPECT_NEAR(glm::dot(sn.normals[2], n0), 1.0f, 1e-6f);    // its corner off the edge: flat
    EXPECT_NEAR(glm::dot(sn.normals[5], n1), 1.0f, 1e-6f);
  }
}

TEST(SmoothNormals, AnApexBeyondTheBoundStaysFlatAndIsCounted) {
  // A cone of n facets: its apex holds n distinct face normals.
  const int n = 64;
  std::vector<glm::vec3> p = {{0, 0, 1}};
  for (int i = 0; i <= n; ++i) p.push_back({std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n), 0});
  std::vector<glm::uvec3> tris;
  for (int i = 0; i < n; ++i) tris.push_back({0, unsigned(i + 1), unsigned(i + 2)});
  SmoothNormals bounded = smoothCornerNormals(p, tris, 60.0f, n - 1);
  SmoothNormals smooth = smoothCornerNormals(p, tris, 60.0f, n);
  EXPECT_EQ(bounded.flatPositions, 1);
  EXPECT_EQ(smooth.flatPositions, 0);
  for (int t = 0; t < n; ++t) {
    EXPECT_NEAR(glm::dot(bounded.normals[t * 3], faceNormal(p, tris[t])), 1.0f, 1e-6f);
    // Facets 45 deg from the axis: within 60 deg of each other up to 90 deg around, so the apex's
    // normal leans toward the axis (z) beyond the facet's own.
    EXPECT_GT(smooth.normals[t * 3].z, faceNormal(p, tris[t]).z + 0.05f);
    EXPECT_EQ(bounded.normals[t * 3 + 1], smooth.normals[t * 3 + 1]);  // the rim: fewer than the bound
  }
}

TEST(SmoothNormals, TheLoaderGivesAnObjWithoutNormalsTheSameNormalsAsBefore) {
  // Through loadScene: one normal per corner, equal to assimp's rule (as the loader used it until now).
  const std::string path = writeShapesObj(testing::TempDir() + "shapes_loaded.obj");
  Scene s = loadScene(path);
  ASSERT_EQ(s.meshes.size(), 1u);
  const Mesh& m = s.meshes[0];
  ASSERT_EQ(m.normals.size(), m.positions.size());
  Assimp::Importer importer;
  importer.SetPropertyFloat(AI_CONFIG_PP_GSN_MAX_SMOOTHING_ANGLE, 60.0f);
  const aiScene* ai = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_GenSmoothNormals);
  const aiMesh* am = ai->mMeshes[0];
  ASSERT_EQ(m.triangles.size(), am->mNumFaces);
  for (unsigned f = 0; f < am->mNumFaces; ++f)
    for (int k = 0; k < 3; ++k) {
      const aiVector3D& a = am->mNormals[am->mFaces[f].mIndices[k]];
      ASSERT_GT(glm::dot(m.normals[m.triangles[f][k]], glm::vec3(a.x, a.y, a.z)), 1.0f - 1e-6f);
    }
}

}  // namespace vgi
