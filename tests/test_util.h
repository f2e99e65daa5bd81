// Helpers shared by the tests: data paths and small analytic scenes.
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <glm/gtc/packing.hpp>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image.h"
#include "core/scene.h"

namespace vgi::test {

// The value a half-float texel stores for x, and one half-float step of x
// (the CPU's rounding of ties may differ from the GL's).
inline float toHalf(float x) { return glm::unpackHalf1x16(glm::packHalf1x16(x)); }
inline float halfStep(float x) { return std::max(std::abs(x) * (1.0f / 1024.0f), 1.0f / 16777216.0f); }
// GPU texels against the CPU's values, within a half-float step each.
inline void compareHalf(const std::vector<glm::vec4>& gpu, const std::vector<glm::vec4>& cpu,
                        const std::string& what) {
  ASSERT_EQ(gpu.size(), cpu.size()) << what;
  int bad = 0;
  for (size_t i = 0; i < gpu.size(); ++i)
    for (int k = 0; k < 4; ++k)
      if (std::abs(gpu[i][k] - toHalf(cpu[i][k])) > halfStep(cpu[i][k]) && bad++ < 5)
        ADD_FAILURE() << what << " texel " << i << " c" << k << ": " << gpu[i][k] << " vs " << cpu[i][k];
  EXPECT_EQ(bad, 0) << what;
}

inline std::string dataPath(const std::string& rel) { return std::string(VGI_TEST_DATA) + "/" + rel; }

// A scene file from ../shared/scenes, or "" when that data is absent (tests then skip).
inline std::string sharedScene(const std::string& rel) {
  std::string p = std::string(VGI_SHARED_SCENES) + "/" + rel;
  return std::filesystem::exists(p) ? p : "";
}

// Expects `fn` to throw vgi::Error whose message contains every needle.
template <typename Fn>
void expectError(Fn fn, std::initializer_list<std::string> needles) {
  try {
    fn();
    ADD_FAILURE() << "expected vgi::Error";
  } catch (const Error& e) {
    std::string msg = e.what();
    for (auto& n : needles) EXPECT_NE(msg.find(n), std::string::npos) << "'" << n << "' not in: " << msg;
  }
}

// Mean of one colour channel over an image.
inline double meanOf(const Image& img, int channel = 0) {
  double s = 0;
  for (auto& p : img.pixels) s += p[channel];
  return s / double(img.pixels.size());
}

// The mean and the unbiased sample variance of v (at least two values).
inline void meanAndVariance(const std::vector<double>& v, double& mean, double& var) {
  mean = 0;
  for (double x : v) mean += x;
  mean /= double(v.size());
  var = 0;
  for (double x : v) var += (x - mean) * (x - mean);
  var /= double(v.size() - 1);
}

// Appends to out[b] the mean (over pixels and colour channels) of each block×block block b of img
// (row-major blocks; out sized to the block count) — one sample per seed for the block-mean t-tests.
inline void addBlockMeans(const Image& img, int block, std::vector<std::vector<double>>& out) {
  const int nx = img.width / block, ny = img.height / block;
  out.resize(size_t(nx * ny));
  for (int by = 0; by < ny; ++by)
    for (int bx = 0; bx < nx; ++bx) {
      double s = 0;
      for (int y = by * block; y < (by + 1) * block; ++y)
        for (int x = bx * block; x < (bx + 1) * block; ++x) {
          const glm::vec3 p = img.at(x, y);
          s += (p.x + p.y + p.z) / 3.0;
        }
      out[size_t(by * nx + bx)].push_back(s / (block * block));
    }
}

inline int addMaterial(Scene& s, glm::vec3 albedo, glm::vec3 emission = glm::vec3(0.0f)) {
  Material m;
  m.name = "m" + std::to_string(s.materials.size());
  m.albedo = albedo;
  m.emission = emission;
  s.materials.push_back(m);
  return int(s.materials.size()) - 1;
}

// A mesh with its own grey Lambert material.
inline Mesh& addMesh(Scene& s, std::vector<glm::vec3> positions, std::vector<glm::uvec3> triangles) {
  Mesh m;
  m.name = "mesh" + std::to_string(s.meshes.size());
  m.source = "test";
  m.material = addMaterial(s, glm::vec3(0.5f));
  m.positions = std::move(positions);
  m.triangles = std::move(triangles);
  s.meshes.push_back(std::move(m));
  return s.meshes.back();
}

// The mean pixel of an image.
inline glm::dvec3 meanColor(const Image& im) {
  glm::dvec3 s(0.0);
  for (auto& p : im.pixels) s += glm::dvec3(p);
  return s / double(im.pixels.size());
}

// One red triangle (albedo 0.8, 0.1, 0.1) facing the camera under a constant grey sky (0.5, 0.25, 1)
// and no lights: every gathering ray escapes, so the indirect light is albedo × sky wherever the
// triangle is seen (the centre 8×8 pixels of a 32² image see only it). Returns its path, TempDir/NAME.json:
// one name per test, since the suite's tests run as parallel processes that share TempDir.
inline std::string writeSkyTriangleScene(const std::string& name) {
  std::string path = testing::TempDir() + "/" + name + ".json";
  std::ofstream(path) << R"({
    "meshes": [ {"path": ")"
                      << dataPath("triangle.gltf") << R"("} ],
    "environment": {"color": [0.5, 0.25, 1.0]},
    "camera": {"position": [0.3, 0.3, 0], "target": [0.3, 0.3, 2], "fov_deg": 30} })";
  return path;
}

// A scene JSON: the built-in Cornell box plus a small triangle (tests/data/triangle.gltf)
// that moves by (0.3, 0.2, 0) between times 0 and 1. Returns its path.
inline std::string writeMovingTriangleScene(const std::string& name) {
  std::string path = testing::TempDir() + "/" + name + ".json";
  std::ofstream(path) << R"({ "meshes": [ {"path": "builtin:cornell"},
      {"path": ")" << dataPath("triangle.gltf")
                      << R"(", "transform": {"scale": 0.2, "translate": [0.1, 0.1, -0.3]},
       "dynamic": true, "keyframes": [ {"time": 0, "translate": [0, 0, 0]}, {"time": 1, "translate": [0.3, 0.2, 0]} ] } ] })";
  return path;
}

// Axis-aligned quad in the plane y = `y`, spanning [-h, h] in x and z.
inline void addFloor(Scene& s, float h, float y, int material) {
  Mesh m;
  m.name = "floor";
  m.source = "test";
  m.positions = {{-h, y, -h}, {h, y, -h}, {h, y, h}, {-h, y, h}};
  m.triangles = {{0, 2, 1}, {0, 3, 2}};
  m.material = material;
  s.meshes.push_back(m);
}

// Closed axis-aligned box [lo, hi]; the faces wind counter-clockwise seen from
// inside, so one-sided emission lights the inside (the furnace test).
inline void addBox(Scene& s, glm::vec3 lo, glm::vec3 hi, int material) {
  Mesh m;
  m.name = "box";
  m.source = "test";
  for (int i = 0; i < 8; ++i)
    m.positions.push_back({i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z});
  const unsigned q[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                            {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
  for (auto& f : q) {
    m.triangles.push_back({f[0], f[1], f[2]});
    m.triangles.push_back({f[0], f[2], f[3]});
  }
  m.material = material;
  s.meshes.push_back(m);
}

}  // namespace vgi::test
