// The exact voxelizer on hard cases, against oracles that do not use the
// separating-axis test: dense point sampling (every sampled point's cell must be
// set) and a distance bound (every set cell's centre lies within half a cell
// diagonal of a triangle), plus hand-computed answers.
#include "voxelize/exact_voxelizer.h"

#include <random>

#include "core/scene_loader.h"
#include "test_util.h"
#include "voxelize/grid_metrics.h"

namespace vgi {

namespace {
// A scene of triangles given directly in grid coordinates of `box` (axis-aligned, origin 0, unit cells).
Scene gridScene(const std::vector<std::array<glm::vec3, 3>>& tris) {
  Scene s;
  test::addMaterial(s, glm::vec3(0.5f));
  Mesh m;
  m.source = "test";
  for (auto& t : tris) {
    uint32_t b = uint32_t(m.positions.size());
    m.positions.insert(m.positions.end(), t.begin(), t.end());
    m.triangles.push_back({b, b + 1, b + 2});
  }
  s.meshes.push_back(m);
  return s;
}
GridBox unitBox(glm::uvec3 res) {
  GridBox b;
  b.resolution = res;
  b.extent = glm::vec3(res);
  return b;
}
double pointTriangleDistance(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  // Ericson, Real-Time Collision Detection §5.1.5 (closest point on triangle).
  glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return glm::length(p - a);
  glm::dvec3 bp = p - b;
  double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return glm::length(p - b);
  double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return glm::length(p - (a + ab * (d1 / (d1 - d3))));
  glm::dvec3 cp = p - c;
  double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return glm::length(p - c);
  double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return glm::length(p - (a + ac * (d2 / (d2 - d6))));
  double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return glm::length(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
  double denom = 1.0 / (va + vb + vc);
  return glm::length(p - (a + ab * (vb * denom) + ac * (vc * denom)));
}
// Checks the grid of `tris` against both oracles.
void checkAgainstOracles(const std::vector<std::array<glm::vec3, 3>>& tris, glm::uvec3 res) {
  Scene s = gridScene(tris);
  GridBox box = unitBox(res);
  BinaryGrid g = voxelizeExact(s, box);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  for (auto& t : tris)
    for (int i = 0; i < 20000; ++i) {
      double a = u(rng), b = u(rng);
      if (a + b > 1) a = 1 - a, b = 1 - b;
      glm::dvec3 p = glm::dvec3(t[0]) + a * glm::dvec3(t[1] - t[0]) + b * glm::dvec3(t[2] - t[0]);
      if (p.x < 0 || p.y < 0 || p.z < 0 || p.x > res.x || p.y > res.y || p.z > res.z) continue;
      glm::uvec3 c = glm::min(glm::uvec3(glm::floor(p)), res - 1u);
      ASSERT_TRUE(g.test(c.x, c.y, c.z))
          << "sampled point's cell missing: " << c.x << "," << c.y << "," << c.z;
    }
  for (uint32_t z = 0; z < res.z; ++z)
    for (uint32_t y = 0; y < res.y; ++y)
      for (uint32_t x = 0; x < res.x; ++x) {
        if (!g.test(x, y, z)) continue;
        double best = 1e30;
        for (auto& t : tris)
          best = std::min(best, pointTriangleDistance(glm::dvec3(x, y, z) + 0.5, t[0], t[1], t[2]));
        ASSERT_LE(best, std::sqrt(3.0) / 2 + 1e-9)
            << "cell too far from every triangle: " << x << "," << y << "," << z;
      }
}
}  // namespace

TEST(VoxelGrid, BitRangeNeverShiftsBy32) {
  using shared::bitRange;
  EXPECT_EQ(bitRange(0u, 31u), 0xffffffffu);
  EXPECT_EQ(bitRange(0u, 0u), 1u);
  EXPECT_EQ(bitRange(31u, 31u), 0x80000000u);
  EXPECT_EQ(bitRange(5u, 9u), 0x3e0u);
  for (uint32_t a = 0; a < 32; ++a)
    for (uint32_t b = a; b < 32; ++b) EXPECT_EQ(uint32_t(__builtin_popcount(bitRange(a, b))), b - a + 1);
}

TEST(VoxelGrid, LayoutMatchesTheSlabConvention) {
  GridBox box = unitBox({4, 3, 256});
  BinaryGrid g(box);
  g.set(1, 2, 0);
  g.set(1, 2, 33);   // word 1 = slab 0, component 1
  g.set(1, 2, 130);  // word 4 = slab 1, component 0
  EXPECT_EQ(g.words()[((0 * 3 + 2) * 4 + 1) * 4 + 0], 1u);
  EXPECT_EQ(g.words()[((0 * 3 + 2) * 4 + 1) * 4 + 1], 2u);
  EXPECT_EQ(g.words()[((1 * 3 + 2) * 4 + 1) * 4 + 0], 4u);
  EXPECT_EQ(g.count(), 3u);
  EXPECT_EQ(g.columnCount(1, 2), 3u);
}

TEST(VoxelGrid, ResolutionParsingAndMemoryLimits) {
  EXPECT_EQ(parseResolution("256"), glm::uvec3(256));
  EXPECT_EQ(parseResolution("64x32x512"), glm::uvec3(64, 32, 512));
  test::expectError([] { parseResolution("100"); }, {"--voxels", "100", "128"});
  test::expectError([] { parseResolution("64x64"); }, {"64x64"});
  test::expectError([] { parseResolution("0x4x128"); }, {"0x4x128"});
  test::expectError([] { parseResolution("64x64x2048"); }, {"2048"});
  test::expectError([] { checkGridMemory({8192, 8192, 1024}, 4); }, {"8192x8192x1024", "MiB"});
}

// The cells a world box covers, on an axis-aligned and a rotated grid: every point of the box lies
// in a cell of the range (the margins widen it exactly), nothing outside the grid, empty bounds
// give an empty range.
TEST(VoxelGrid, BoundsCellsCoverTheBoxThroughTheGridsAxes) {
  GridBox box;
  box.origin = glm::vec3(-1.0f, 2.0f, 0.5f);
  box.extent = glm::vec3(2.0f, 1.0f, 4.0f);
  box.resolution = {32, 16, 128};
  Bounds b;
  b.extend({-0.31f, 2.27f, 1.13f});
  b.extend({0.42f, 2.61f, 2.9f});
  const CellRange r = boundsCells(box, b, 0, 1);
  // x: (-0.31 + 1) / 2 * 32 = 11.04 … (0.42 + 1) / 2 * 32 = 22.72: cells 11 … 22.
  EXPECT_EQ(r.lo, glm::uvec3(11, 4, 20));
  EXPECT_EQ(r.hi, glm::uvec3(23, 10, 77));
  const CellRange wide = boundsCells(box, b, 2, 3);
  EXPECT_EQ(wide.lo, r.lo - 2u);
  EXPECT_EQ(wide.hi, r.hi + 2u);
  Bounds huge;
  huge.extend(glm::vec3(-1e20f));
  huge.extend(glm::vec3(1e20f));
  EXPECT_EQ(boundsCells(box, huge, 1, 2).hi, box.resolution);
  EXPECT_EQ(boundsCells(box, huge, 1, 2).lo, glm::uvec3(0));
  EXPECT_EQ(boundsCells(box, Bounds{}, 1, 2).count(), 0u);
  // Rotated: sample the box; each point's cell is inside the range.
  box.axes = glm::mat3_cast(glm::angleAxis(0.7f, glm::normalize(glm::vec3(1, 2, 3))));
  box.origin = glm::vec3(-2.0f, 0.5f, -1.0f);
  const CellRange rr = boundsCells(box, b, 0, 1);
  EXPECT_GT(rr.count(), 0u);
  const shared::GridParams g = box.params();
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j)
      for (int k = 0; k <= 10; ++k) {
        const glm::vec3 p = glm::mix(b.lo, b.hi, glm::vec3(i, j, k) / 10.0f);
        const glm::vec3 q = shared::offsetToGrid(g, p - box.origin);
        if (!shared::insideGrid(g, q)) continue;
        const glm::uvec3 c = shared::gridCell(g, q);
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(c, rr.lo)) && glm::all(glm::lessThan(c, rr.hi)))
            << i << "," << j << "," << k;
      }
}

TEST(ExactVoxelizer, TinyTriangleInsideOneCell) {
  Scene s = gridScene({{{{3.2f, 4.3f, 5.4f}, {3.3f, 4.3f, 5.4f}, {3.2f, 4.35f, 5.45f}}}});
  BinaryGrid g = voxelizeExact(s, unitBox({8, 8, 128}));
  EXPECT_EQ(g.count(), 1u);
  EXPECT_TRUE(g.test(3, 4, 5));
}

TEST(ExactVoxelizer, AxisAlignedQuadOnACellBoundarySetsBothSides) {
  auto quad = [](float z) {
    return std::vector<std::array<glm::vec3, 3>>{{{{2.25f, 2.25f, z}, {6.75f, 2.25f, z}, {6.75f, 6.75f, z}}},
                                                 {{{2.25f, 2.25f, z}, {6.75f, 6.75f, z}, {2.25f, 6.75f, z}}}};
  };
  EXPECT_EQ(voxelizeExact(gridScene(quad(5.5f)), unitBox({8, 8, 128})).count(), 25u);  // one layer
  BinaryGrid on = voxelizeExact(gridScene(quad(5.0f)), unitBox({8, 8, 128}));
  EXPECT_EQ(on.count(), 50u);  // closed cells: layers 4 and 5
  EXPECT_TRUE(on.test(2, 2, 4) && on.test(6, 6, 5));
  // On the grid's upper boundary only the last layer exists.
  EXPECT_EQ(voxelizeExact(gridScene(quad(128.0f)), unitBox({8, 8, 128})).count(), 25u);
  // Edges exactly on x = 2 and x = 7 boundaries: columns 1…7 touched.
  std::vector<std::array<glm::vec3, 3>> aligned = {{{{2, 2.5f, 9.5f}, {7, 2.5f, 9.5f}, {7, 3.5f, 9.5f}}}};
  BinaryGrid e = voxelizeExact(gridScene(aligned), unitBox({8, 8, 128}));
  EXPECT_TRUE(e.test(1, 2, 9) && e.test(7, 3, 9));
  checkAgainstOracles(quad(5.0f), {8, 8, 128});
}

TEST(ExactVoxelizer, DepthAcrossWordAndSlabBorders) {
  // A thin sliver along z through the middle of column (2, 3).
  auto sliver = [](float z0, float z1) {
    return std::vector<std::array<glm::vec3, 3>>{{{{2.5f, 3.5f, z0}, {2.5f, 3.5f, z1}, {2.5001f, 3.5f, z1}}}};
  };
  BinaryGrid w = voxelizeExact(gridScene(sliver(30.5f, 33.5f)), unitBox({4, 4, 256}));
  EXPECT_EQ(w.count(), 4u);
  for (uint32_t z = 30; z <= 33; ++z) EXPECT_TRUE(w.test(2, 3, z)) << z;
  BinaryGrid s = voxelizeExact(gridScene(sliver(126.5f, 129.5f)), unitBox({4, 4, 256}));
  EXPECT_EQ(s.count(), 4u);
  for (uint32_t z = 126; z <= 129; ++z) EXPECT_TRUE(s.test(2, 3, z)) << z;
  checkAgainstOracles(sliver(100.2f, 300.0f), {4, 4, 256});  // leaves the grid
}

TEST(ExactVoxelizer, HugeSlantedAndSliverTriangles) {
  checkAgainstOracles({{{{-10, -5, -20}, {50, 3, 140}, {7, 40, 60}}}}, {32, 24, 128});
  checkAgainstOracles({{{{0.1f, 0.1f, 0.1f}, {31.9f, 23.9f, 127.9f}, {31.9f, 23.9001f, 127.9f}}}},
                      {32, 24, 128});
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-2, 34);
  std::vector<std::array<glm::vec3, 3>> many;
  for (int i = 0; i < 40; ++i)
    many.push_back(
        {{{u(rng), u(rng), u(rng) * 4}, {u(rng), u(rng), u(rng) * 4}, {u(rng), u(rng), u(rng) * 4}}});
  checkAgainstOracles(many, {32, 32, 128});
}

TEST(ExactVoxelizer, NonCubicOrientedGridAndFlatScene) {
  // A rotated grid box: the same triangles expressed in a rotated frame give the same cells.
  // Generic vertices: integer ones put edges exactly on cell edges, where rounding decides.
  std::vector<std::array<glm::vec3, 3>> tris = {
      {{{1.37f, 2.21f, 3.53f}, {20.13f, 5.71f, 100.29f}, {9.61f, 30.17f, 50.83f}}}};
  GridBox box = unitBox({24, 32, 128});
  BinaryGrid ref = voxelizeExact(gridScene(tris), box);
  glm::mat3 R = glm::mat3_cast(glm::angleAxis(0.7f, glm::normalize(glm::vec3(1, 2, 3))));
  std::vector<std::array<glm::vec3, 3>> rotated;
  for (auto& t : tris)
    rotated.push_back(
        {R * t[0] + glm::vec3(5, 6, 7), R * t[1] + glm::vec3(5, 6, 7), R * t[2] + glm::vec3(5, 6, 7)});
  GridBox rbox = box;
  rbox.axes = R;
  rbox.origin = glm::vec3(5, 6, 7);
  BinaryGrid rot = voxelizeExact(gridScene(rotated), rbox);
  GridComparison c = compareGrids(rot, ref);
  EXPECT_GT(c.recall(), 0.999);  // float rounding of the rotation may flip boundary-touching cells
  EXPECT_GT(c.precision(), 0.999);

  Scene flat;
  test::addFloor(flat, 1.0f, 0.25f, test::addMaterial(flat, glm::vec3(0.5f)));
  GridBox fb = fitGridBox(flat, {64, 64, 128});
  EXPECT_GT(fb.extent.y, 0.0f);
  BinaryGrid fg = voxelizeExact(flat, fb);
  EXPECT_EQ(fg.count(), 64u * 128u);  // one layer: the plane is not on a cell boundary
}

TEST(ExactVoxelizer, ThreadCountDoesNotChangeTheGrid) {
  std::vector<std::array<glm::vec3, 3>> many;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0, 64);
  for (int i = 0; i < 500; ++i)
    many.push_back(
        {{{u(rng), u(rng), u(rng) * 2}, {u(rng), u(rng), u(rng) * 2}, {u(rng), u(rng), u(rng) * 2}}});
  Scene s = gridScene(many);
  EXPECT_EQ(voxelizeExact(s, unitBox({64, 64, 128}), 0, 1).words(),
            voxelizeExact(s, unitBox({64, 64, 128}), 0, 2).words());
}

}  // namespace vgi

namespace vgi {
// Shrinking keeps every cell centred: a quad through the middle of layer 5 stays
// in it; one 0.2 above its floor leaves the ¼-shrunk cell [5.25, 5.75].
TEST(ExactVoxelizer, ShrunkCellsStayCentred) {
  auto quad = [](float z) {
    return std::vector<std::array<glm::vec3, 3>>{{{{2.3f, 2.3f, z}, {6.7f, 2.3f, z}, {6.7f, 6.7f, z}}},
                                                 {{{2.3f, 2.3f, z}, {6.7f, 6.7f, z}, {2.3f, 6.7f, z}}}};
  };
  EXPECT_EQ(voxelizeExact(gridScene(quad(5.5f)), unitBox({8, 8, 128}), 0, 0, 0.25).count(), 25u);
  EXPECT_EQ(voxelizeExact(gridScene(quad(5.2f)), unitBox({8, 8, 128}), 0, 0, 0.25).count(), 0u);
  EXPECT_EQ(voxelizeExact(gridScene(quad(5.8f)), unitBox({8, 8, 128}), 0, 0, 0.25).count(), 0u);
  EXPECT_EQ(voxelizeExact(gridScene(quad(5.2f)), unitBox({8, 8, 128})).count(), 25u);
}
}  // namespace vgi

namespace vgi {
// Surfaces on the scene's bounds (walls of a box) must be inside the fitted
// grid under any rounding: here a tiny object just below the floor moves the
// box's lower bound by 1e-5, which used to put the ceiling a hair outside the
// grid for the double-precision exact voxelizer (but not for float ones).
TEST(ExactVoxelizer, SurfacesOnTheFittedBoundsStayInside) {
  Scene s = loadScene("builtin:cornell");
  test::addMesh(s, {{0.40f, -1.26e-5f, 0.10f}, {0.41f, 0.01f, 0.10f}, {0.40f, 0.01f, 0.11f}}, {{0, 1, 2}});
  GridBox box = fitGridBox(s, glm::uvec3(128));
  BinaryGrid g = voxelizeExact(s, box);
  uint32_t ceiling = 0, floorCells = 0;
  for (uint32_t z = 0; z < 128; ++z)
    for (uint32_t x = 0; x < 128; ++x) {
      ceiling += g.test(x, 127, z);
      floorCells += g.test(x, 0, z);
    }
  EXPECT_GT(ceiling, 128u * 100u);  // the ceiling spans (almost) the whole top layer
  EXPECT_GT(floorCells, 128u * 100u);
}
}  // namespace vgi
