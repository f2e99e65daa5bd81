// The voxel tracers on hard cases (DESIGN.md): the hierarchical tracer must
// equal the DDA oracle (same hit, voxel and distance) on more than a million
// random and adversarial rays per run; the DDA must agree with an exact
// double-precision ray–box test; GLSL on llvmpipe must equal the C++ build
// bit for bit; no NaN and no loop beyond its proven bound; 10^7 adversarial
// rays finish.
#include "traverse/ray_tracers.h"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>

#include "core/gl_context.h"
#include "core/profiler.h"
#include "core/scene_loader.h"
#include "core/shader_library.h"
#include "shaders/shared/trace_bricks.glsl"
#include "shaders/shared/trace_hierarchical.glsl"
#include "shaders/shared/tracer_ids.glsl"
#include "test_util.h"
#include "traverse/brick_tree.h"
#include "traverse/gl_ray_tracer.h"
#include "traverse/or_mip_pyramid.h"
#include "traverse/ray_population.h"
#include "voxelize/exact_voxelizer.h"
#include "voxelize/voxel_grid.h"
#include "voxelize/voxelizer.h"

namespace vgi {

namespace {

const float kInf = std::numeric_limits<float>::infinity();

struct TestGrid {
  std::string name;
  GridBox box;
  double density;
};

// Unit cells at the origin (world == grid coordinates, so adversarial origins
// land exactly on faces), non-cubic cells, and a rotated, offset box.
std::vector<TestGrid> testGrids() {
  std::vector<TestGrid> grids;
  auto add = [&](std::string name, glm::uvec3 res, glm::vec3 extent, glm::mat3 axes, glm::vec3 origin,
                 double density) {
    GridBox b;
    b.resolution = res;
    b.extent = extent;
    b.axes = axes;
    b.origin = origin;
    grids.push_back({std::move(name), b, density});
  };
  const glm::mat3 id(1.0f);
  const float c = std::cos(0.6f), s = std::sin(0.6f);
  glm::mat3 rot(glm::vec3(c, s, 0.0f), glm::vec3(-s * 0.8f, c * 0.8f, 0.6f), glm::vec3(0.0f));
  rot[2] = glm::normalize(glm::cross(rot[0], rot[1]));
  rot[1] = glm::normalize(rot[1]);
  add("unit 32x32x128", {32, 32, 128}, {32, 32, 128}, id, glm::vec3(0.0f), 0.003);
  add("unit 48x17x256", {48, 17, 256}, {48, 17, 256}, id, glm::vec3(0.0f), 0.001);
  add("non-cubic 37x20x512", {37, 20, 512}, {2.0f, 1.3f, 0.7f}, id, glm::vec3(-1.0f, 0.25f, 3.0f), 0.0008);
  add("rotated 64x64x1024", {64, 64, 1024}, {1.0f, 1.0f, 1.0f}, rot, glm::vec3(0.3f, -0.2f, 0.1f), 0.0002);
  add("flat 1x1x128", {1, 1, 128}, {0.5f, 0.5f, 4.0f}, id, glm::vec3(0.0f), 0.05);
  add("unit 256x256x256 sparse", {256, 256, 256}, {256, 256, 256}, id, glm::vec3(0.0f), 0.00002);
  return grids;
}

// Random voxels plus a wall and a floor, so rays both hit early and travel far.
BinaryGrid fillGrid(const TestGrid& tg, uint32_t seed) {
  BinaryGrid g(tg.box);
  glm::uvec3 r = tg.box.resolution;
  std::mt19937 rng(seed);
  std::bernoulli_distribution bit(tg.density);
  for (uint32_t z = 0; z < r.z; ++z)
    for (uint32_t y = 0; y < r.y; ++y)
      for (uint32_t x = 0; x < r.x; ++x)
        if (bit(rng)) g.set(x, y, z);
  for (uint32_t y = 0; y < r.y; ++y)
    for (uint32_t z = 0; z < r.z; ++z) g.set(r.x - 1, y, z);  // wall at the far x end
  for (uint32_t x = 0; x < r.x / 2; ++x)
    for (uint32_t z = 0; z < r.z; z += 3) g.set(x, 0, z);  // a comb on the y = 0 floor
  return g;
}

glm::vec3 gridToWorld(const GridBox& b, glm::vec3 q) {
  glm::vec3 local = q * b.voxelSize();
  return b.origin + b.axes * local;
}

// Adversarial rays in grid coordinates, mapped to world space.
std::vector<TraceRay> adversarialRays(const GridBox& box, size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  std::uniform_int_distribution<int> pick(0, 1 << 20);
  glm::vec3 res(box.resolution);
  std::vector<TraceRay> rays(n);
  const float diag = glm::length(box.extent);
  for (size_t i = 0; i < n; ++i) {
    int kind = pick(rng) % 10;
    glm::vec3 q;
    for (int a = 0; a < 3; ++a) q[a] = u01(rng) * res[a];
    glm::vec3 d(u01(rng) * 2 - 1, u01(rng) * 2 - 1, u01(rng) * 2 - 1);
    int axis = pick(rng) % 3;
    switch (kind) {
      case 0:
        break;  // random inside
      case 1:   // outside, up to one box away on every side
        for (int a = 0; a < 3; ++a) q[a] = (u01(rng) * 3 - 1) * res[a];
        break;
      case 2:  // on a face, edge or corner of a voxel
        for (int a = 0; a < 3; ++a)
          if (pick(rng) % 2) q[a] = std::floor(q[a]);
        break;
      case 3:  // axis-parallel, other components +0 or −0
        d = glm::vec3(pick(rng) % 2 ? 0.0f : -0.0f, pick(rng) % 2 ? 0.0f : -0.0f,
                      pick(rng) % 2 ? 0.0f : -0.0f);
        d[axis] = pick(rng) % 2 ? 1.0f : -1.0f;
        if (pick(rng) % 2) q = glm::floor(q);
        break;
      case 4:  // grazing: in a voxel face plane, moving inside it
        q[axis] = std::floor(q[axis]);
        d[axis] = pick(rng) % 2 ? 0.0f : -0.0f;
        break;
      case 5:  // on the grid boundary, any direction
        q[axis] = pick(rng) % 2 ? 0.0f : res[axis];
        break;
      case 6:  // tiny components
        d[axis] = (pick(rng) % 2 ? 1.0f : -1.0f) * (pick(rng) % 2 ? 1e-30f : 1e-8f);
        break;
      case 7:  // diagonal through voxel corners
        q = glm::floor(q);
        d = glm::vec3(pick(rng) % 2 ? 1 : -1, pick(rng) % 2 ? 1 : -1, pick(rng) % 2 ? 1 : -1);
        break;
      case 8:  // far outside, aimed at the grid
        q = res * 0.5f + glm::normalize(d) * (glm::length(res) * 50.0f);
        d = res * glm::vec3(u01(rng), u01(rng), u01(rng)) - q;
        break;
      default:  // on an edge of the grid box
        q[axis] = 0.0f;
        q[(axis + 1) % 3] = res[(axis + 1) % 3];
        break;
    }
    if (d == glm::vec3(0.0f)) d[axis] = 1.0f;
    TraceRay& r = rays[i];
    r.origin = gridToWorld(box, q);
    glm::vec3 wd = box.axes * (d * box.voxelSize());
    r.dir = glm::normalize(wd);
    if (!std::isfinite(r.dir.x)) r.dir = box.axes[axis];
    switch (pick(rng) % 6) {
      case 0:
        r.tmax = 0.0f;
        break;
      case 1:
        r.tmax = kInf;
        break;
      case 2:
        r.tmax = 1e30f;
        break;
      case 3:
        r.tmax = u01(rng) * 0.05f * diag;
        break;
      default:
        r.tmax = u01(rng) * 2.0f * diag;
        break;
    }
  }
  return rays;
}

struct Mismatch {
  size_t count = 0;
  std::string first;
};

void compare(const std::vector<TraceResult>& a, const std::vector<TraceResult>& b,
             const std::vector<TraceRay>& rays, const GridBox& box, bool compareSteps, Mismatch& m) {
  const float tol = 1e-5f * std::min(box.voxelSize().x, std::min(box.voxelSize().y, box.voxelSize().z));
  for (size_t i = 0; i < a.size(); ++i) {
    bool same = a[i].hit == b[i].hit &&
                (!a[i].hit || (a[i].voxel == b[i].voxel && std::abs(a[i].t - b[i].t) <= tol)) &&
                (!compareSteps || (a[i].steps == b[i].steps && (!a[i].hit || a[i].t == b[i].t)));
    if (!same && m.count++ == 0) {
      std::ostringstream s;
      s.precision(9);
      s << "ray " << i << " o=(" << rays[i].origin.x << "," << rays[i].origin.y << "," << rays[i].origin.z
        << ") d=(" << rays[i].dir.x << "," << rays[i].dir.y << "," << rays[i].dir.z
        << ") tmax=" << rays[i].tmax << ": hit " << a[i].hit << "/" << b[i].hit << " t " << a[i].t << "/"
        << b[i].t << " voxel (" << a[i].voxel.x << "," << a[i].voxel.y << "," << a[i].voxel.z << ")/("
        << b[i].voxel.x << "," << b[i].voxel.y << "," << b[i].voxel.z << ") steps " << a[i].steps << "/"
        << b[i].steps;
      m.first = s.str();
    }
  }
}

}  // namespace

TEST(RayTracers, HierarchicalEqualsDdaOnAMillionAdversarialRays) {
  size_t total = 0, hits = 0;
  for (const TestGrid& tg : testGrids()) {
    BinaryGrid g = fillGrid(tg, 11);
    OrMipPyramid pyramid(g);
    TracerInputs in;
    in.pyramid = &pyramid;
    auto hier = createTracer("hierarchical", in), dda = createTracer("dda", in);
    std::vector<TraceRay> rays = adversarialRays(tg.box, 200000, 5);
    std::vector<TraceResult> h, d;
    hier->traceBatch(rays, h);
    dda->traceBatch(rays, d);
    Mismatch m;
    compare(h, d, rays, tg.box, false, m);
    EXPECT_EQ(m.count, 0u) << tg.name << ": first mismatch " << m.first;
    const glm::uvec3 r = tg.box.resolution;
    const uint32_t hierBound = shared::hierarchicalMaxSteps(r.x, r.y, pyramid.levels());
    size_t exact = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      ASSERT_LE(h[i].steps, hierBound) << tg.name << " ray " << i;
      ASSERT_LE(d[i].steps, r.x + r.y + r.z + 3) << tg.name << " ray " << i;
      ASSERT_FALSE(std::isnan(h[i].t)) << tg.name << " ray " << i;
      if (h[i].hit) {
        ++hits;
        ASSERT_TRUE(g.test(h[i].voxel.x, h[i].voxel.y, h[i].voxel.z));
        ASSERT_LE(h[i].t, rays[i].tmax);
        exact += h[i].t == d[i].t;
      }
    }
    // Both evaluate the same plane parameters, so the distances are identical, not just close.
    size_t hitCount = 0;
    for (auto& x : h) hitCount += x.hit;
    EXPECT_EQ(exact, hitCount) << tg.name;
    total += rays.size();
  }
  EXPECT_GE(total, 1000000u);
  EXPECT_GT(hits, total / 10);  // the population must exercise hits, not only misses
}

// The 4³ bricks (step 4 of issue "Speed on the GL device"): every node's bit is the OR of its child
// cube's cells, and the tracer's first hit equals the DDA's — voxel and distance, bit for bit — on the
// adversarial rays of every test grid (faces, edges, corners, axis-parallel and tiny directions).
TEST(RayTracers, BricksEqualDdaOnAdversarialRays) {
  size_t total = 0, hits = 0;
  for (const TestGrid& tg : testGrids()) {
    BinaryGrid g = fillGrid(tg, 11);
    OrMipPyramid pyramid(g);
    BrickTree tree(pyramid);
    const shared::BrickTreeParams& p = tree.params();
    const glm::uvec3 r = tg.box.resolution;
    for (uint32_t s = 1; s <= p.levels; ++s) {  // every bit against its cube, by brute force on level 1
      const uint32_t nx = shared::bricksPerAxis(r.x, s), ny = shared::bricksPerAxis(r.y, s),
                     nz = shared::bricksPerAxis(r.z, s);
      for (uint32_t z = 0; z < nz; ++z)
        for (uint32_t y = 0; y < ny; ++y)
          for (uint32_t x = 0; x < nx; ++x)
            for (uint32_t bit = 0; bit < 64; ++bit) {
              const uint32_t w = shared::brickWordIndex(p, s, x, y, z, bit);
              const bool set = (tree.words()[w] >> (bit & 31u)) & 1u;
              const uint32_t side = 1u << (2u * (s - 1u));
              const glm::uvec3 lo =
                  glm::uvec3(4u * x + (bit & 3u), 4u * y + ((bit >> 2u) & 3u), 4u * z + (bit >> 4u)) * side;
              bool any = false;
              if (s == 1)
                any = lo.x < r.x && lo.y < r.y && lo.z < r.z && g.test(lo.x, lo.y, lo.z);
              else if (s == 2)  // level 2 against the cells directly (higher levels follow by induction)
                for (uint32_t k = lo.z; k < std::min(lo.z + side, r.z) && !any; ++k)
                  for (uint32_t j = lo.y; j < std::min(lo.y + side, r.y) && !any; ++j)
                    for (uint32_t i = lo.x; i < std::min(lo.x + side, r.x) && !any; ++i)
                      any = g.test(i, j, k);
              else
                continue;
              ASSERT_EQ(set, any) << tg.name << " level " << s << " node " << x << "," << y << "," << z
                                  << " bit " << bit;
            }
    }
    TracerInputs in;
    in.pyramid = &pyramid;
    auto bricks = createTracer("bricks", in), dda = createTracer("dda", in);
    std::vector<TraceRay> rays = adversarialRays(tg.box, 200000, 5);
    std::vector<TraceResult> b, d;
    bricks->traceBatch(rays, b);
    dda->traceBatch(rays, d);
    Mismatch m;
    compare(b, d, rays, tg.box, false, m);
    EXPECT_EQ(m.count, 0u) << tg.name << ": first mismatch " << m.first;
    const uint32_t bound = shared::bricksMaxSteps(r.x, r.y, r.z, p.levels);
    for (size_t i = 0; i < rays.size(); ++i) {
      ASSERT_LE(b[i].steps, bound) << tg.name << " ray " << i;
      if (b[i].hit) {
        ++hits;
        ASSERT_EQ(b[i].t, d[i].t) << tg.name << " ray " << i;  // the same planes through the same planeT
      }
    }
    total += rays.size();
  }
  EXPECT_GE(total, 1000000u);
  EXPECT_GT(hits, total / 10);
}

// vgi bench traverse's counts (shared::TraceCounts) follow the traversal they count: counting changes no
// result; the DDA and the march load one word per voxel they test, the hierarchical tracer one per word
// of a column range it searches; a hierarchical hit ends at level 0, so it refined as often as it
// climbed (it starts there too), a miss at most as often. Empty and full grids pin the extremes.
TEST(RayTracers, TraversalCountsFollowTheTraversal) {
  for (const TestGrid& tg : testGrids()) {
    BinaryGrid g = fillGrid(tg, 13);
    OrMipPyramid pyramid(g);
    TracerInputs in;
    in.pyramid = &pyramid;
    const std::vector<TraceRay> rays = adversarialRays(tg.box, 20000, 9);
    for (const char* name : {"hierarchical", "dda", "march"}) {
      auto tracer = createTracer(name, in);
      std::vector<TraceResult> plain, counted;
      std::vector<shared::TraceCounts> c;
      tracer->traceBatch(rays, plain);
      tracer->countBatch(rays, counted, c);
      ASSERT_EQ(c.size(), rays.size());
      size_t climbed = 0;
      for (size_t i = 0; i < rays.size(); ++i) {
        ASSERT_EQ(plain[i].hit, counted[i].hit) << tg.name << " " << name << " ray " << i;
        ASSERT_EQ(plain[i].steps, counted[i].steps) << tg.name << " " << name << " ray " << i;
        ASSERT_EQ(c[i].bytes, 4u * c[i].fetches) << tg.name << " " << name;
        if (std::string(name) == "hierarchical") {
          if (counted[i].hit) {
            ASSERT_EQ(c[i].refines, c[i].climbs) << tg.name << " ray " << i;
          }
          ASSERT_LE(c[i].refines, c[i].climbs) << tg.name << " ray " << i;
          ASSERT_LE(c[i].climbs, counted[i].steps) << tg.name << " ray " << i;
          climbed += c[i].climbs;
        } else {
          // One voxel tested per step, but for the last when the ray leaves the grid or ends.
          ASSERT_LE(c[i].fetches, counted[i].steps) << tg.name << " " << name << " ray " << i;
          ASSERT_GE(c[i].fetches + 1u, counted[i].steps) << tg.name << " " << name << " ray " << i;
          ASSERT_EQ(c[i].climbs + c[i].refines, 0u);
        }
      }
      if (std::string(name) == "hierarchical" && pyramid.levels() > 1) {
        EXPECT_GT(climbed, 0u) << tg.name;
      }
    }
  }
  // An empty grid: the hierarchical tracer climbs to the top and leaves; a ray across a 128³ grid
  // along x reads one word per column it visits, far fewer than the DDA's 128 cells.
  TestGrid tg = testGrids().front();
  BinaryGrid empty(tg.box);
  OrMipPyramid pyramid(empty);
  TracerInputs in;
  in.pyramid = &pyramid;
  TraceRay ray;
  const glm::vec3 lo = tg.box.origin, ext = tg.box.extent;
  ray.origin = lo + glm::vec3(-0.01f * ext.x, 0.37f * ext.y, 0.41f * ext.z);
  ray.dir = glm::vec3(1, 0, 0);
  ray.tmax = INFINITY;
  std::vector<TraceResult> h, d;
  std::vector<shared::TraceCounts> ch, cd;
  createTracer("hierarchical", in)->countBatch({ray}, h, ch);
  createTracer("dda", in)->countBatch({ray}, d, cd);
  ASSERT_FALSE(h[0].hit);
  EXPECT_EQ(cd[0].fetches, tg.box.resolution.x) << tg.name;
  EXPECT_LT(ch[0].fetches, cd[0].fetches / 4) << tg.name;
  EXPECT_GE(ch[0].climbs, 1u);
  EXPECT_EQ(ch[0].refines, 0u);
}

// The DDA against geometry computed in double: with one voxel set, a ray hits it
// iff the segment overlaps the voxel's box, at the box entry distance. Rays that
// only graze the box (overlap within 1e-4 of a voxel) are decided by the
// definition's tie rules and skipped.
TEST(RayTracers, DdaMatchesExactRayBoxOverlap) {
  for (const TestGrid& tg : testGrids()) {
    if (tg.box.resolution.x < 8) continue;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    size_t checked = 0, hits = 0;
    for (int trial = 0; trial < 40; ++trial) {
      BinaryGrid g(tg.box);
      glm::uvec3 v(uint32_t(u01(rng) * tg.box.resolution.x), uint32_t(u01(rng) * tg.box.resolution.y),
                   uint32_t(u01(rng) * tg.box.resolution.z));
      g.set(v.x, v.y, v.z);
      OrMipPyramid pyramid(g);
      TracerInputs in;
      in.pyramid = &pyramid;
      auto dda = createTracer("dda", in), hier = createTracer("hierarchical", in);
      const glm::dvec3 cell = glm::dvec3(tg.box.voxelSize());
      for (int i = 0; i < 500; ++i) {
        // Aim near the voxel from a random point in the grid.
        glm::dvec3 qo(u01(rng) * tg.box.resolution.x, u01(rng) * tg.box.resolution.y,
                      u01(rng) * tg.box.resolution.z);
        glm::dvec3 qt =
            glm::dvec3(v) + glm::dvec3(u01(rng) * 1.6 - 0.3, u01(rng) * 1.6 - 0.3, u01(rng) * 1.6 - 0.3);
        glm::dvec3 lo = glm::dvec3(tg.box.origin), wo = lo + glm::dmat3(tg.box.axes) * (qo * cell);
        glm::dvec3 wt = lo + glm::dmat3(tg.box.axes) * (qt * cell);
        glm::dvec3 dir = glm::normalize(wt - wo);
        TraceRay ray;
        ray.origin = glm::vec3(wo);
        ray.dir = glm::vec3(dir);
        ray.tmax = float(glm::length(wt - wo) * (u01(rng) < 0.5 ? 0.9 : 1.5));
        // Exact slab test in grid space with the float inputs the tracer sees.
        glm::dvec3 o = glm::transpose(glm::dmat3(tg.box.axes)) * (glm::dvec3(ray.origin) - lo) / cell;
        glm::dvec3 d = glm::transpose(glm::dmat3(tg.box.axes)) * glm::dvec3(ray.dir) / cell;
        double t0 = 0.0, t1 = ray.tmax;
        for (int a = 0; a < 3; ++a) {
          double ta = (v[a] - o[a]) / d[a], tb = (v[a] + 1.0 - o[a]) / d[a];
          t0 = std::max(t0, std::min(ta, tb));
          t1 = std::min(t1, std::max(ta, tb));
        }
        const double overlap = t1 - t0, eps = 1e-4 * std::min(cell.x, std::min(cell.y, cell.z));
        if (std::abs(overlap) < eps) continue;
        TraceResult r = dda->trace(ray), rh = hier->trace(ray);
        ++checked;
        ASSERT_EQ(r.hit, overlap > 0)
            << tg.name << " trial " << trial << " ray " << i << " overlap " << overlap;
        ASSERT_EQ(rh.hit, r.hit);
        if (r.hit) {
          ++hits;
          EXPECT_EQ(r.voxel, v);
          EXPECT_NEAR(r.t, t0, 1e-4 * glm::length(glm::dvec3(tg.box.extent))) << tg.name;
        }
      }
    }
    EXPECT_GT(checked, 15000u) << tg.name;
    EXPECT_GT(hits, checked / 10) << tg.name;
  }
}

// Hand-picked cases with known answers on a 4×4×1024 unit grid.
TEST(RayTracers, HardCasesHaveTheDefinedAnswers) {
  GridBox box;
  box.resolution = {4, 4, 1024};
  box.extent = glm::vec3(box.resolution);
  BinaryGrid g(box);
  for (uint32_t k : {31u, 32u, 127u, 128u, 1023u}) g.set(1, 2, k);
  g.set(3, 3, 0);
  OrMipPyramid pyramid(g);
  TracerInputs in;
  in.pyramid = &pyramid;
  for (const char* name : {"hierarchical", "dda"}) {
    SCOPED_TRACE(name);
    auto tr = createTracer(name, in);
    auto trace = [&](glm::vec3 o, glm::vec3 d, float tmax) {
      TraceRay r;
      r.origin = o;
      r.dir = d;
      r.tmax = tmax;
      return tr->trace(r);
    };
    // Along +z and −z through a column: bits in several words and slabs.
    TraceResult h = trace({1.5f, 2.5f, 0.0f}, {0.0f, 0.0f, 1.0f}, kInf);
    EXPECT_TRUE(h.hit);
    EXPECT_EQ(h.voxel, glm::uvec3(1, 2, 31));
    EXPECT_EQ(h.t, 31.0f);
    h = trace({1.5f, 2.5f, 31.5f}, {-0.0f, 0.0f, 1.0f}, kInf);  // starts inside a set voxel: t = 0
    EXPECT_EQ(h.voxel.z, 31u);
    EXPECT_EQ(h.t, 0.0f);
    h = trace({1.5f, 2.5f, 33.0f}, {0.0f, -0.0f, 1.0f}, kInf);
    EXPECT_EQ(h.voxel.z, 127u);
    h = trace({1.5f, 2.5f, 1000.0f}, {0.0f, 0.0f, -1.0f}, kInf);
    EXPECT_EQ(h.voxel.z, 128u);
    EXPECT_EQ(h.t, 1000.0f - 129.0f);
    h = trace({1.5f, 2.5f, 2000.0f}, {0.0f, 0.0f, -1.0f}, kInf);  // from outside, against the depth axis
    EXPECT_EQ(h.voxel.z, 1023u);
    EXPECT_EQ(h.t, 2000.0f - 1024.0f);
    // tmax: ends exactly on the entry plane of a set voxel (the end point counts) or just before.
    EXPECT_TRUE(trace({1.5f, 2.5f, 0.0f}, {0.0f, 0.0f, 1.0f}, 31.0f).hit);
    EXPECT_FALSE(trace({1.5f, 2.5f, 0.0f}, {0.0f, 0.0f, 1.0f}, 30.999f).hit);
    EXPECT_FALSE(trace({1.5f, 2.5f, 0.5f}, {0.0f, 0.0f, 1.0f}, 0.0f).hit);  // tmax = 0 in an empty voxel
    EXPECT_TRUE(trace({1.5f, 2.5f, 31.5f}, {0.0f, 0.0f, 1.0f}, 0.0f).hit);  // … and in a set one
    // The grid's upper faces belong to the last cells (closed box).
    h = trace({4.0f, 4.0f, -5.0f}, {0.0f, 0.0f, 1.0f}, kInf);
    EXPECT_TRUE(h.hit);
    EXPECT_EQ(h.voxel, glm::uvec3(3, 3, 0));
    // A diagonal exactly through the shared corner of (2,3,0) and (3,3,0)'s neighbours.
    h = trace({2.0f, 2.0f, 0.5f}, glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f)), kInf);
    EXPECT_TRUE(h.hit);
    EXPECT_EQ(h.voxel, glm::uvec3(3, 3, 0));  // steps (2,2) → (3,3), never (2,3) or (3,2)
    // Pointing away, NaN and infinite inputs, zero direction: misses, never NaN.
    EXPECT_FALSE(trace({1.5f, 2.5f, -1.0f}, {0.0f, 0.0f, -1.0f}, kInf).hit);
    EXPECT_FALSE(trace({NAN, 2.5f, 0.0f}, {0.0f, 0.0f, 1.0f}, kInf).hit);
    EXPECT_FALSE(trace({1.5f, 2.5f, 0.0f}, {NAN, 0.0f, 1.0f}, kInf).hit);
    EXPECT_FALSE(trace({1.5f, 2.5f, 0.0f}, {0.0f, 0.0f, 1.0f}, NAN).hit);
    EXPECT_FALSE(trace({1.5f, 2.5f, 0.0f}, {0.0f, 0.0f, 1.0f}, -1.0f).hit);
    EXPECT_FALSE(trace({kInf, 2.5f, 0.0f}, {0.0f, 0.0f, 1.0f}, kInf).hit);
    EXPECT_FALSE(trace({1.5f, 2.5f, 0.0f}, {0.0f, 0.0f, 0.0f}, kInf).hit);
    // A denormal component counts as zero (1/d would be inf).
    h = trace({1.5f, 2.5f, 0.0f}, {1e-40f, -1e-40f, 1.0f}, kInf);
    EXPECT_EQ(h.voxel, glm::uvec3(1, 2, 31));
  }
  // Two-point visibility: the same loop ending at the second point.
  shared::PyramidParams p = pyramidParams(pyramid);
  EXPECT_FALSE(
      shared::visibleHierarchical(p, {1.5f, 2.5f, 0.0f}, {1.5f, 2.5f, 40.0f}, pyramid.words().data()));
  EXPECT_TRUE(
      shared::visibleHierarchical(p, {1.5f, 2.5f, 0.0f}, {1.5f, 2.5f, 30.5f}, pyramid.words().data()));
  EXPECT_TRUE(
      shared::visibleHierarchical(p, {0.5f, 0.5f, 0.0f}, {0.5f, 3.5f, 900.0f}, pyramid.words().data()));
}

TEST(RayTracers, GlslOnLlvmpipeEqualsCppBitForBit) {
  auto gl = GlContext::create();
  ShaderLibrary shaders;
  Profiler profiler(true);
  for (const TestGrid& tg : testGrids()) {
    if (tg.box.resolution.x == 256) continue;  // keep the llvmpipe run short
    BinaryGrid g = fillGrid(tg, 17);
    OrMipPyramid pyramid(g);
    GlPyramid gpu(pyramid);
    TracerInputs in;
    in.pyramid = &pyramid;
    std::vector<TraceRay> rays = adversarialRays(tg.box, 20000, 23);
    for (const char* name : {"hierarchical", "dda", "march"}) {
      std::vector<TraceResult> cpu;
      createTracer(name, in)->traceBatch(rays, cpu);
      std::vector<TraceResult> glr = traceRaysGl(gpu, shaders, name, rays, profiler);
      Mismatch m;
      compare(glr, cpu, rays, tg.box, true, m);
      EXPECT_EQ(m.count, 0u) << tg.name << " " << name << ": " << m.first;
    }
  }
  EXPECT_EQ(gl->errorCount(), 0);
  test::expectError(
      [&] {
        std::vector<TraceRay> r;
        ShaderDefines d;
        addTracerDefine(d, "embree");
      },
      {"tracer 'embree'", "no GLSL"});
  test::expectError([] { findTracer("octree"); },
                    {"tracer 'octree'", "hierarchical", "dda", "march", "embree"});
  // An id that names no tracer is a compile error in GLSL, not a silent `march`.
  test::expectError(
      [&] {
        shaders.program({"traverse/trace_rays.comp.glsl"}, {{"VGI_TRACER", "7"}});
      },
      {"trace_rays.comp.glsl", "unknown VGI_TRACER"});
  EXPECT_EQ(findTracer("dda").define, VGI_TRACER_DDA);
}

// 10^7 adversarial rays through a deep, mostly empty grid: must finish (the
// loop bounds hold) and never exceed the bound.
TEST(RayTracers, StressTenMillionRaysFinish) {
  GridBox box;
  box.resolution = {128, 96, 1024};
  box.extent = {1.0f, 0.75f, 2.0f};
  TestGrid tg{"stress", box, 0.00001};
  BinaryGrid g = fillGrid(tg, 99);
  OrMipPyramid pyramid(g);
  TracerInputs in;
  in.pyramid = &pyramid;
  auto hier = createTracer("hierarchical", in);
  const uint32_t bound = shared::hierarchicalMaxSteps(128, 96, pyramid.levels());
  size_t done = 0, maxSteps = 0;
  for (int batch = 0; batch < 10; ++batch) {
    std::vector<TraceRay> rays = adversarialRays(box, 1000000, 1000 + batch);
    std::vector<TraceResult> out;
    hier->traceBatch(rays, out);
    for (const TraceResult& r : out) {
      ASSERT_LE(r.steps, bound);
      ASSERT_FALSE(std::isnan(r.t));
      maxSteps = std::max<size_t>(maxSteps, r.steps);
    }
    done += out.size();
  }
  EXPECT_EQ(done, 10000000u);
  RecordProperty("max_steps", int(maxSteps));
  RecordProperty("step_bound", int(bound));
}

// A mip level as a grid (pyramidFromLevel, the `voxels` view's level
// parameter): from level l up, the hierarchical tracer must still equal the
// DDA over that level's columns, bit for bit; each hit column must hold a set
// level-0 voxel at its depth cell; and the level is conservative: a ray that
// hits the grid hits the level no later (its planes are the grid's planes at
// multiples of 2^l, so the column holding the fine hit is entered no later).
TEST(RayTracers, FromAMipLevelTheTracersSeeItsColumns) {
  size_t checked = 0, coarseHits = 0, earlier = 0;
  for (const TestGrid& tg : testGrids()) {
    BinaryGrid g = fillGrid(tg, 23);
    OrMipPyramid pyramid(g);
    TracerInputs in;
    in.pyramid = &pyramid;
    std::vector<TraceRay> rays = adversarialRays(tg.box, 20000, 9);
    std::vector<TraceResult> fine;
    createTracer("dda", in)->traceBatch(rays, fine);
    const float tol = 1e-4f * glm::length(tg.box.voxelSize());
    for (uint32_t l = 1; l < uint32_t(pyramid.levels()); ++l) {
      const shared::PyramidParams pl = shared::pyramidFromLevel(pyramidParams(pyramid), l);
      ASSERT_EQ(pl.levels, uint32_t(pyramid.levels()) - l);
      ASSERT_EQ(pl.levelOffsets[0], pyramidParams(pyramid).levelOffsets[l]);
      in.level = l;
      std::vector<TraceResult> h, d;
      createTracer("hierarchical", in)->traceBatch(rays, h);
      createTracer("dda", in)->traceBatch(rays, d);
      Mismatch m;
      compare(h, d, rays, tg.box, false, m);
      ASSERT_EQ(m.count, 0u) << tg.name << " level " << l << ": first mismatch " << m.first;
      const uint32_t side = 1u << l;
      for (size_t i = 0; i < rays.size(); ++i) {
        if (d[i].hit) {
          ++coarseHits;
          ASSERT_EQ(h[i].t, d[i].t) << tg.name << " level " << l << " ray " << i;
          bool set = false;
          const glm::uvec3 v = d[i].voxel, r = tg.box.resolution;
          for (uint32_t y = v.y * side; y < std::min(r.y, (v.y + 1) * side) && !set; ++y)
            for (uint32_t x = v.x * side; x < std::min(r.x, (v.x + 1) * side) && !set; ++x)
              set = g.test(x, y, v.z);
          ASSERT_TRUE(set) << tg.name << " level " << l << " ray " << i << ": column (" << v.x << "," << v.y
                           << ") depth " << v.z << " holds no set voxel";
        }
        if (fine[i].hit) {
          ASSERT_TRUE(d[i].hit) << tg.name << " level " << l << " ray " << i
                                << ": the grid is hit, the level not";
          // (rays from far outside are rebased to the level's larger box: a few ulps of t apart)
          ASSERT_LE(d[i].t, fine[i].t + tol + 1e-6f * fine[i].t) << tg.name << " level " << l << " ray " << i;
          earlier += d[i].t < fine[i].t - tol;
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 100000u);
  EXPECT_GT(earlier, checked / 100);  // the coarse levels do hit earlier: the test sees the difference
  RecordProperty("coarse_hits", int(coarseHits));
  // The GLSL tracers from a level (the `voxels` view's path) on llvmpipe: bit for bit the C++ ones.
  auto gl = GlContext::create();
  ShaderLibrary shaders;
  Profiler profiler(true);
  for (const TestGrid& tg : testGrids()) {
    if (tg.box.resolution.x == 256) continue;  // keep the llvmpipe run short
    OrMipPyramid pyramid(fillGrid(tg, 23));
    GlPyramid gpu(pyramid);
    TracerInputs in;
    in.pyramid = &pyramid;
    in.level = std::min(2u, uint32_t(pyramid.levels()) - 1);
    std::vector<TraceRay> rays = adversarialRays(tg.box, 10000, 31);
    for (const char* name : {"hierarchical", "dda"}) {
      std::vector<TraceResult> cpu;
      createTracer(name, in)->traceBatch(rays, cpu);
      Mismatch m;
      compare(traceRaysGl(gpu, shaders, name, rays, profiler, in.level), cpu, rays, tg.box, true, m);
      EXPECT_EQ(m.count, 0u) << tg.name << " " << name << " level " << in.level << ": " << m.first;
    }
  }
  EXPECT_EQ(gl->errorCount(), 0);
}

}  // namespace vgi

namespace vgi {
// Near-field rays that go on past a hit voxel (nearfield's passthrough): each
// hit is traced again from just past the voxel's exit (shared voxelExitT),
// three times. The resumed rays start a hair past a voxel face, inside the
// grid; hierarchical must still equal the DDA on every one of them.
TEST(RayTracers, ResumedPastAHitVoxelHierarchicalEqualsDda) {
  Scene scene = loadScene("builtin:cornell");
  GridBox box = fitGridBox(scene, glm::uvec3(128), 0.0f);
  auto gl = GlContext::create();
  ShaderLibrary shaders;
  Profiler profiler(true);
  // The grid nearfield traces by default: the atlas voxelizer's (conservative footprints).
  VoxelizeRequest vreq;
  vreq.scene = &scene;
  vreq.box = box;
  vreq.gl = gl.get();
  vreq.shaders = &shaders;
  vreq.atlasCacheDir = "";
  nlohmann::json vstats;
  OrMipPyramid pyramid(findVoxelizer("atlas").run(vreq, profiler, vstats));
  TracerInputs in;
  in.pyramid = &pyramid;
  auto hier = createTracer("hierarchical", in), dda = createTracer("dda", in);
  const float diag = glm::length(box.voxelSize());
  RayPopulation pop;
  pop.count = 200000;
  pop.tmax = 0.5f * scene.bounds().diagonal();
  pop.offset = 0.5f * diag;
  pop.viewpoint = scene.camera.position;
  std::vector<TraceRay> rays = surfaceRays(flatten(scene, 0.0f), pop);
  const shared::GridParams g = pyramid.box().params();
  size_t resumed = 0, mismatches = 0;
  std::string first;
  std::vector<TraceRay> all;  // every ray traced, resumed ones included: for the GLSL check below
  for (TraceRay ray : rays) {
    for (int k = 0; k < 4; ++k) {
      if (all.size() < 100000) all.push_back(ray);
      TraceResult h = hier->trace(ray), d = dda->trace(ray);
      if (h.hit != d.hit || (h.hit && (h.voxel != d.voxel || h.t != d.t))) {
        if (mismatches++ == 0) {
          std::ostringstream s;
          s.precision(9);
          s << "step " << k << " o=(" << ray.origin.x << "," << ray.origin.y << "," << ray.origin.z << ") d=("
            << ray.dir.x << "," << ray.dir.y << "," << ray.dir.z << ") tmax " << ray.tmax << ": t " << h.t
            << "/" << d.t << " voxel (" << h.voxel.x << "," << h.voxel.y << "," << h.voxel.z << ")/("
            << d.voxel.x << "," << d.voxel.y << "," << d.voxel.z << ")";
          first = s.str();
        }
        break;
      }
      if (!h.hit) break;
      shared::GridRay gr = shared::prepareGridRay(g, ray.origin, ray.dir, ray.tmax);
      float start = shared::voxelExitT(gr, h.voxel) + 1e-4f * diag;
      if (start >= ray.tmax) break;
      ray.origin += start * ray.dir;
      ray.tmax -= start;
      ++resumed;
    }
  }
  EXPECT_EQ(mismatches, 0u) << "first: " << first;
  EXPECT_GT(resumed, rays.size() / 2);
  // The GLSL tracers on llvmpipe, on the same rays: bit for bit the C++ ones.
  GlPyramid gpu(pyramid);
  for (const char* name : {"hierarchical", "dda"}) {
    std::vector<TraceResult> cpu;
    createTracer(name, in)->traceBatch(all, cpu);
    Mismatch m;
    compare(traceRaysGl(gpu, shaders, name, all, profiler), cpu, all, box, true, m);
    EXPECT_EQ(m.count, 0u) << name << ": " << m.first;
  }
}
}  // namespace vgi
