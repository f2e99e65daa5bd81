// vpl (illum/methods/vpl.cpp) on its hard cases: the flux tree's descent draws texels
// exactly in proportion to their flux (shared code, C++), the VPL geometry
// term on back faces, an occluder between the VPLs and a receiver (voxel,
// exact and no visibility), voxel against exact visibility on a scene whose
// voxelization is exact, determinism, 0 and 1 VPLs, chains that leave the grid,
// and llvmpipe's per-invocation loop limit (many chains per pixel). The closed
// sphere (analytic_sphere_test.cpp) checks the one- and two-bounce energy.
#include "shaders/shared/vpl.glsl"

#include <cmath>
#include <fstream>
#include <random>

#include "render_util.h"
#include "test_util.h"

namespace vgi {

namespace {

using namespace vgi::shared;

// A floor (y = 0) and a ceiling (y = 1) over [0,1]², a spot light at y = 0.8
// pointing up at the ceiling, and a plate at y = 0.5 over x < xPlate (none
// when 0): the floor sees the lit ceiling only past the plate. The camera
// looks at the floor from the open front (z < 0), under the plate. Every
// surface lies on a plane of a 128³ grid over the unit cube.
const char* const kUpSpot =
    R"({"type": "spot", "position": [0.5, 0.8, 0.5], "direction": [0, 1, 0], "cone_deg": 50, "intensity": 1})";

std::string writePlateScene(const std::string& name, float xPlate, const std::string& light = kUpSpot) {
  const std::string dir = testing::TempDir();
  std::ofstream(dir + "/" + name + ".mtl") << "newmtl white\nKd 0.8 0.8 0.8\n";
  std::ofstream obj(dir + "/" + name + ".obj");
  obj << "mtllib " << name << ".mtl\nusemtl white\n"
      << "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\n"  // floor, facing up
      << "v 0 1 0\nv 1 1 0\nv 1 1 1\nv 0 1 1\n"  // ceiling, facing down
      << "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\n";
  if (xPlate > 0)
    obj << "v 0 0.5 0\nv " << xPlate << " 0.5 0\nv " << xPlate << " 0.5 1\nv 0 0.5 1\nf 9 11 10\nf 9 12 11\n";
  obj.close();
  const std::string path = dir + "/" + name + ".json";
  std::ofstream(path) << R"({ "meshes": [ {"path": ")" << dir << "/" << name << R"(.obj"} ],
    "lights": [ )" << light
                      << R"( ],
    "camera": {"position": [0.5, 0.3, -0.6], "target": [0.5, 0, 0.5], "fov_deg": 40} })";
  return path;
}

double indirectMean(const RenderOutput& r) { return test::meanOf(r.result.aovs.at("indirect"), 1); }

}  // namespace

// Hierarchical warping maps [0,1)² onto the texels with areas equal to their
// share of the flux: a fine regular grid of u lands on each texel in
// proportion to it, and never on a texel without flux (sizes not powers of 2).
TEST(Vpl, FluxTreeDescentDrawsTexelsInProportionToTheirFlux) {
  for (uint32_t res : {1u, 5u, 37u, 64u}) {
    const uint32_t levels = fluxTreeLevels(res), faces = 2;
    ASSERT_EQ(fluxTreeSize(res, levels - 1), 1u);
    std::vector<float> tree(size_t(faces) * fluxTreeFaceStride(res), 0.0f);
    std::mt19937 rng(res);
    std::uniform_real_distribution<float> value(0.0f, 1.0f);
    for (uint32_t f = 0; f < faces; ++f) {
      float* face = tree.data() + size_t(f) * fluxTreeFaceStride(res);
      for (uint32_t i = 0; i < res * res; ++i) face[i] = value(rng) < 0.3f ? 0.0f : value(rng);
      face[0] = 1.0f;  // not all zero
      for (uint32_t l = 1; l < levels; ++l) {
        const uint32_t s = fluxTreeSize(res, l), c = fluxTreeSize(res, l - 1);
        for (uint32_t y = 0; y < s; ++y)
          for (uint32_t x = 0; x < s; ++x) {
            float sum = 0;
            for (uint32_t dy = 0; dy < 2; ++dy)
              for (uint32_t dx = 0; dx < 2; ++dx)
                if (2 * x + dx < c && 2 * y + dy < c)
                  sum += face[fluxTreeOffset(res, l - 1) + (2 * y + dy) * c + 2 * x + dx];
            face[fluxTreeOffset(res, l) + y * s + x] = sum;
          }
      }
    }
    const float* face1 = tree.data() + fluxTreeFaceStride(res);
    const double total = fluxTreeNode(res, 1, levels - 1, 0, 0, tree.data());
    const int n = 1024;
    std::vector<double> hits(size_t(res) * res, 0.0);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const uvec2 t = fluxTreeDescend(res, 1, vec2((i + 0.5f) / n, (j + 0.5f) / n), tree.data());
        ASSERT_LT(t.x, res);
        ASSERT_LT(t.y, res);
        ASSERT_GT(face1[t.y * res + t.x], 0.0f) << "a texel without flux was drawn, res " << res;
        hits[t.y * res + t.x] += 1.0 / (double(n) * n);
      }
    // The lattice of u resolves each texel's region to about its perimeter / n:
    // measured to 1 % up to ~1000 texels at n = 1024 (res 64 is checked for zero-flux texels only).
    double tv = 0;
    for (uint32_t i = 0; i < res * res; ++i) tv += std::abs(hits[i] - face1[i] / total);
    if (res <= 37) {
      EXPECT_LT(0.5 * tv, 0.01) << "total variation distance from the flux distribution, res " << res;
    }
  }
}

// The gathered light of a VPL: the cosine-weighted inverse-square term, zero
// behind the VPL's surface or the receiver's, clamped at dMin.
TEST(Vpl, GatherTermIsZeroOnBackFacesAndClampedNearTheVpl) {
  Vpl v;
  v.position = vec4(0, 1, 0, 1);
  v.normal = vec4(0, -1, 0, 0);
  v.flux = vec4(2, 2, 2, 0);
  v.origin = uvec4(0);
  const vec3 below = vplGather(v, vec3(0, 0, 0), vec3(0, 1, 0), 0.0f);
  EXPECT_NEAR(below.x, 2.0 / (M_PI * M_PI), 1e-6);
  EXPECT_EQ(vplGather(v, vec3(0, 2, 0), vec3(0, -1, 0), 0.0f), vec3(0.0f)) << "receiver behind the VPL";
  EXPECT_EQ(vplGather(v, vec3(0, 0, 0), vec3(0, -1, 0), 0.0f), vec3(0.0f)) << "receiver facing away";
  EXPECT_NEAR(vplGather(v, vec3(0, 0, 0), vec3(0, 1, 0), 4.0f).x, 2.0 / (M_PI * M_PI) / 4.0, 1e-6) << "clamp";
  v.position.w = 0.0f;
  EXPECT_EQ(vplGather(v, vec3(0, 0, 0), vec3(0, 1, 0), 0.0f), vec3(0.0f)) << "empty slot";
}

// A plate between the lit ceiling and the whole floor: no VPL reaches the
// floor through any visibility — vpl's voxel and exact, avg's shadow maps
// (cube, paraboloid) and exact; without visibility they all do.
TEST(Vpl, AnOccluderBlocksTheVplsInEveryVisibility) {
  const std::string scene = writePlateScene("vpl_plate_full", 1.0f);
  auto floorIndirect = [&](const std::string& method, std::vector<std::string> set) {
    set.push_back("shadow_res=256");
    set.push_back("bounces=1");
    return indirectMean(test::render(scene, method, set, 32, 2, {"indirect"}));
  };
  const double none = floorIndirect("vpl", {"visibility=none"}),
               voxels = floorIndirect("vpl", {"visibility=voxels"}),
               exact = floorIndirect("vpl", {"visibility=exact"}),
               avgNone = floorIndirect("avg", {"visibility=none"}),
               avgCube = floorIndirect("avg", {"shadow_map=cube"}),
               avgPara = floorIndirect("avg", {"shadow_map=paraboloid"}),
               avgExact = floorIndirect("avg", {"visibility=exact"});
  std::printf(
      "floor under a plate: vpl none %.5f, voxels %.5f, exact %.5f; avg none %.5f, cube %.5f, "
      "paraboloid %.5f, exact %.5f\n",
      none, voxels, exact, avgNone, avgCube, avgPara, avgExact);
  EXPECT_GT(none, 1e-3);
  EXPECT_LT(voxels, 0.01 * none);
  EXPECT_LT(exact, 0.01 * none);
  EXPECT_GT(avgNone, 1e-3);
  EXPECT_LT(avgCube, 0.01 * avgNone);
  EXPECT_LT(avgPara, 0.01 * avgNone);
  EXPECT_LT(avgExact, 0.01 * avgNone);
}

// Half a plate: the floor is partly shadowed from the ceiling's VPLs. With an
// exact (triangle–box) voxelization of axis-aligned planes, the voxel two-point
// test agrees with Embree's to within the voxels' conservative thickness.
TEST(Vpl, VoxelVisibilityAgreesWithExactVisibilityOnAnExactVoxelization) {
  const std::string scene = writePlateScene("vpl_plate_half", 0.5f);
  auto render = [&](const std::string& visibility) {
    return test::render(
        scene, "vpl",
        {"bounces=1", "visibility=" + visibility, "voxelizer=exact", "shadow_res=256", "vpls=256"}, 48, 4,
        {"indirect"});
  };
  const RenderOutput none = render("none"), voxels = render("voxels"), exact = render("exact");
  const double n = indirectMean(none), v = indirectMean(voxels), e = indirectMean(exact);
  std::printf("floor beside half a plate: indirect none %.5f, voxels %.5f, exact %.5f\n", n, v, e);
  EXPECT_LT(e, 0.9 * n) << "the plate must shadow part of the floor";
  EXPECT_NEAR(v / e, 1.0, 0.05);
}

// The same seed gives the same VPLs and image; another seed other VPLs.
TEST(Vpl, TheVplSetIsDeterministicForASeed) {
  RenderOptions o;
  o.scene = "builtin:cornell";
  o.method = "vpl";
  o.set = {"shadow_res=256", "vpls=64"};
  o.width = o.height = 32;
  o.spp = 2;
  o.progress = false;
  const RenderOutput a = runRender(o), b = runRender(o);
  o.seed = 7;
  const RenderOutput c = runRender(o);
  EXPECT_EQ(a.result.image.pixels, b.result.image.pixels);
  EXPECT_EQ(a.stats["extra"]["vpl_flux"], b.stats["extra"]["vpl_flux"]);
  EXPECT_NE(a.result.image.pixels, c.result.image.pixels);
}

// No VPLs: the image is the deferred pass's, bit for bit the `direct` method's.
TEST(Vpl, ZeroVplsIsTheDirectMethodBitForBit) {
  RenderOutput d = test::render("builtin:cornell", "direct", {"shadow_res=256"}, 32, 2);
  RenderOutput v = test::render("builtin:cornell", "vpl", {"vpls=0", "shadow_res=256"}, 32, 2, {"indirect"});
  EXPECT_EQ(d.result.image.pixels, v.result.image.pixels);
  EXPECT_EQ(test::meanOf(v.result.aovs.at("indirect"), 1), 0.0);
}

// First-bounce VPLs carry the RSMs' reflected flux in all, one VPL or many;
// in the open plate scene most bounce rays leave the grid (the chain ends
// there: fewer second-bounce VPLs, no NaN).
TEST(Vpl, OneOrManyVplsCarryTheReflectedFluxAndChainsEndOutsideTheGrid) {
  const std::string scene = writePlateScene("vpl_plate_none", 0.0f);
  auto run = [&](int n) {
    return test::render(scene, "vpl", {"vpls=" + std::to_string(n), "interleave=1", "shadow_res=256"}, 32, 1,
                        {"indirect"});
  };
  const RenderOutput one = run(1), many = run(512);
  const double fluxOne = one.stats["extra"]["vpl_flux"][0], fluxMany = many.stats["extra"]["vpl_flux"][0];
  // The ceiling receives all of the spot's flux (I(θ) = cos θ in a 50° cone: π sin² 50°); it reflects 0.8 of it.
  const double s = std::sin(50.0 * M_PI / 180.0), reflected = 0.8 * M_PI * s * s;
  EXPECT_NEAR(fluxOne / reflected, 1.0, 0.02);
  EXPECT_NEAR(fluxMany / reflected, 1.0, 0.02);
  const int first = many.stats["extra"]["vpls_placed"][0], second = many.stats["extra"]["vpls_placed"][1];
  EXPECT_EQ(first, 512);
  EXPECT_GT(second, 0);
  EXPECT_LT(second, first) << "rays leaving the open sides place no VPL";
  for (const auto& p : many.result.image.pixels) ASSERT_TRUE(std::isfinite(p.x + p.y + p.z));
}

// A directional light (irradiance E, straight down) lights the top of the
// 1 m² ceiling: both methods' first VPLs carry its reflected flux 0.8 · E —
// vpl from the orthographic RSM face, avg from rays shot from a disc
// across the scene.
TEST(Vpl, ADirectionalLightsVplsCarryItsReflectedFlux) {
  const std::string scene = writePlateScene(
      "vpl_plate_sun", 0.0f, R"({"type": "directional", "direction": [0, -1, 0], "irradiance": 2})");
  for (const char* method : {"vpl", "avg"}) {
    const RenderOutput r = test::render(scene, method, {"shadow_res=256", "vpls=1024"}, 16, 1, {"indirect"});
    const double flux = r.stats["extra"]["vpl_flux"][0];
    EXPECT_NEAR(flux / (0.8 * 2.0), 1.0, 0.02) << method;
  }
}

// 1024 chains in one subset: 1024 per pixel, far past llvmpipe's 65535 loop
// iterations per invocation if the gather ran in one dispatch (it dropped
// ~60 % of them); batched, the indirect light equals that of 16 chains at the
// same samples (the same camera jitters: one sample against 64 differed by 4 %
// at this gather size, whatever the chains), eight seeds' mean (each within about 2 %).
TEST(Vpl, ManyChainsPerPixelAreAllGathered) {
  auto run = [&](int n, uint32_t seed) {
    RenderOptions o = test::options(
        "builtin:cornell", "vpl",
        {"vpls=" + std::to_string(n), "interleave=1", "tracer=dda", "shadow_res=256", "resolution=0.25"}, 32,
        16, {"indirect"});
    o.seed = seed;
    return indirectMean(runRender(o));
  };
  double few = 0;
  for (uint32_t seed = 1; seed <= 8; ++seed) few += run(16, seed) / 8.0;
  EXPECT_NEAR(run(1024, 1) / few, 1.0, 0.03);
}

}  // namespace vgi
