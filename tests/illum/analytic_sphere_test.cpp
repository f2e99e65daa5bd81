// The closed diffuse sphere (radius R, albedo ρ) lit by a point light of
// intensity I at its centre: every wall point receives E = I/R² directly, and
// since each point of a sphere sees the whole wall with the same form factor,
// a wall of uniform radiance L gives every point E = πL; so d bounces give
// L = ρI/(πR²)·(1 + ρ + … + ρ^(d−1)) and the full solution ρI/(πR²(1 − ρ)).
// Each light-transport method against the truncation it computes.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>

#include "render_util.h"
#include "test_util.h"

namespace vgi {

namespace {

constexpr float kR = 1.0f, kRho = 0.5f, kI = 2.0f;

// An icosphere (4 subdivisions: 5120 faces, facets within 6·10⁻⁴ R of the
// sphere) with radial vertex normals, as OBJ + MTL, and a scene JSON with
// the light at the centre and the camera inside.
std::string writeSphereScene() {
  std::vector<glm::vec3> v;
  std::vector<glm::uvec3> f;
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  for (glm::vec3 p : {glm::vec3(-1, t, 0), glm::vec3(1, t, 0), glm::vec3(-1, -t, 0), glm::vec3(1, -t, 0),
                      glm::vec3(0, -1, t), glm::vec3(0, 1, t), glm::vec3(0, -1, -t), glm::vec3(0, 1, -t),
                      glm::vec3(t, 0, -1), glm::vec3(t, 0, 1), glm::vec3(-t, 0, -1), glm::vec3(-t, 0, 1)})
    v.push_back(glm::normalize(p));
  f = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
       {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
       {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int s = 0; s < 4; ++s) {
    std::map<std::pair<unsigned, unsigned>, unsigned> mid;
    auto middle = [&](unsigned a, unsigned b) {
      auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back(glm::normalize(v[a] + v[b]));
      return mid[key] = unsigned(v.size() - 1);
    };
    std::vector<glm::uvec3> next;
    for (auto& tri : f) {
      unsigned a = middle(tri.x, tri.y), b = middle(tri.y, tri.z), c = middle(tri.z, tri.x);
      next.insert(next.end(), {{tri.x, a, c}, {tri.y, b, a}, {tri.z, c, b}, {a, b, c}});
    }
    f = std::move(next);
  }
  const std::string dir = testing::TempDir();
  std::ofstream(dir + "/sphere.mtl") << "newmtl wall\nKd " << kRho << " " << kRho << " " << kRho << "\n";
  std::ofstream obj(dir + "/sphere.obj");
  obj << "mtllib sphere.mtl\n";
  for (auto& p : v)
    obj << "v " << kR * p.x << " " << kR * p.y << " " << kR * p.z << "\nvn " << p.x << " " << p.y << " "
        << p.z << "\n";
  obj << "usemtl wall\n";
  for (auto& tri : f)
    obj << "f " << tri.x + 1 << "//" << tri.x + 1 << " " << tri.y + 1 << "//" << tri.y + 1 << " " << tri.z + 1
        << "//" << tri.z + 1 << "\n";
  obj.close();
  const std::string path = dir + "/sphere.json";
  std::ofstream(path) << R"({ "meshes": [ {"path": ")" << dir << R"(/sphere.obj"} ],
    "lights": [ {"type": "point", "position": [0, 0, 0], "intensity": )"
                      << kI << R"(} ],
    "camera": {"position": [0, 0, 0.3], "target": [0, 0, -1], "fov_deg": 30} })";
  return path;
}

// ρI/(πR²)·(1 + ρ + … + ρ^(d−1)).
double bounces(int d) {
  double sum = 0, p = 1;
  for (int k = 0; k < d; ++k, p *= kRho) sum += p;
  return kRho * kI / (M_PI * kR * kR) * sum;
}

}  // namespace

TEST(AnalyticSphere, EveryLightTransportMethodGivesItsTruncation) {
  const std::string scene = writeSphereScene();
  struct Case {
    const char* method;
    std::vector<std::string> set;
    int spp, bounces;
    double tolerance;  // relative, on the image mean
    const char* why;
  };
  const std::vector<Case> cases = {
      {"reference", {"integrator=direct"}, 16, 1, 0.003, "exact visibility; facets within 6e-4 R"},
      {"reference", {"integrator=nearfield", "radius=3"}, 256, 2, 0.01, "one bounce, Monte Carlo"},
      {"reference", {"integrator=path", "maxdepth=3", "rr_depth=10"}, 256, 3, 0.01, "two bounces"},
      {"reference", {"integrator=path", "maxdepth=10000"}, 256, 10000, 0.015, "the full solution (RR)"},
      // VGI's one-diagonal offset without a pass: the concave wall's own cells stop 2.1 % of the
      // bounce rays short (measured 0.979) — the voxel-visibility stage of voxelpath's error split.
      {"reference",
       {"integrator=path", "maxdepth=3", "rr_depth=10", "visibility=voxels"},
       256,
       3,
       0.03,
       "two bounces, bounce rays through the voxel grid"},
      {"direct", {"shadow_res=256"}, 4, 1, 0.003, "shadow maps: nothing occludes"},
      {"nearfield", {"radius=3", "shadow_res=256"}, 16, 2, 0.02, "voxel visibility + RSM back-projection"},
      {"voxelpath", {"maxdepth=1", "shadow_res=256"}, 4, 1, 0.003, "maxdepth 1 is the direct light"},
      {"voxelpath", {"maxdepth=2", "shadow_res=256"}, 64, 2, 0.02, "one bounce through the grid"},
      {"voxelpath", {"maxdepth=3", "rr_depth=10", "shadow_res=256"}, 64, 3, 0.02, "two bounces, 128^3"},
      {"voxelpath",
       {"maxdepth=3", "rr_depth=10", "shadow_res=256", "voxels=256"},
       64,
       3,
       0.02,
       "two bounces, 256^3"},
      // In a sphere cos θ_v cos θ_x / d² = 1/(4R²) for any two points, so the
      // VPLs' clamp at d_min (0.005 of the box diagonal 2√3 R) removes
      // d_min²/(8R²) = 0.004 % of each bounce: within these tolerances.
      {"vpl", {"bounces=1", "clamp=0", "shadow_res=256"}, 8, 2, 0.01, "RSM VPLs, voxel visibility"},
      {"vpl", {"bounces=2", "clamp=0", "shadow_res=256"}, 8, 3, 0.02, "and one bounce through the grid"},
      {"vpl", {"bounces=2", "shadow_res=256"}, 8, 3, 0.02, "the default clamp"},
      {"vpl", {"bounces=1", "vpls=1", "interleave=1", "shadow_res=256"}, 4, 2, 0.01, "one VPL is exact here"},
      // AVG VPLs sit up to half a cell inside the 64³ cells of the wall (and
      // their maps' centres a cell diagonal along the normal): d² and the
      // cosines shift by a few per cent of R.
      // (Each VPL's shadow map draws the 5120 triangles: paraboloids and 256 VPLs keep it short.)
      {"avg",
       {"bounces=1", "clamp=0", "vpls=256", "shadow_map=paraboloid", "shadow_res=256"},
       8,
       2,
       0.03,
       "light-traced VPLs, AVG, paraboloid maps"},
      {"avg", {"bounces=3", "clamp=0", "visibility=none", "shadow_res=256"}, 8, 4, 0.03, "three bounces, RR"},
      {"avg",
       {"bounces=1", "tracing=exact", "visibility=exact", "shadow_res=256"},
       8,
       2,
       0.01,
       "exact stages"},
      // Cones (128³, anisotropic, |d| face weights): the image is 0.974 of direct + one bounce, i.e.
      // the bounce 0.92 of ρ²I/(πR²) (isotropic: 0.72 of the image); docs/BENCHMARKS.md.
      {"vct", {"shadow_res=256"}, 4, 2, 0.04, "voxel cone tracing, one bounce"},
      {"ddgi",
       {"shadow_res=256"},
       32,
       10000,
       0.02,
       "probes: 8 bounces of warm-up, then the mean of 32 updates"},
      {"voxelpath",
       {"maxdepth=6", "rr_depth=1", "shadow_res=256"},
       128,
       6,
       0.03,
       "five bounces with Russian roulette from the first"},
  };
  for (const Case& c : cases) {
    RenderOutput r = test::render(scene, c.method, c.set, 32, c.spp);
    const double expected = bounces(c.bounces), got = test::meanOf(r.result.image, 0);
    std::printf("closed sphere: %s %s: %.5f of the %d-bounce truncation\n", c.method,
                c.set.empty() ? "" : c.set[0].c_str(), got / expected, c.bounces);
    EXPECT_NEAR(got / expected, 1.0, c.tolerance) << c.method << " " << (c.set.empty() ? "" : c.set[0])
                                                  << " (" << c.why << "): " << got << " vs " << expected;
  }
}

}  // namespace vgi
