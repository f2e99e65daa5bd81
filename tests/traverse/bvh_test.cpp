// The exact triangle tracer (shaders/shared/trace_bvh.glsl, traverse/gpu_bvh.h):
// the C++ build of the shared kernel against Embree (robust mode) on hit/miss
// and t, on a million rays with hard cases on purpose — through vertices and
// edges, grazing a triangle's plane, starting on a surface, ending exactly on
// one, degenerate triangles —, and the GLSL build on llvmpipe against the C++
// one bit for bit.
#include <gtest/gtest.h>

#include <random>
#include <sstream>

#include "core/gl_context.h"
#include "core/profiler.h"
#include "core/scene_loader.h"
#include "core/shader_library.h"
#include "test_util.h"
#include "traverse/embree_tracer.h"
#include "traverse/gl_ray_tracer.h"
#include "traverse/gpu_bvh.h"
#include "traverse/or_mip_pyramid.h"
#include "traverse/ray_tracers.h"
#include "voxelize/exact_voxelizer.h"
#include "voxelize/voxel_grid.h"

namespace vgi {

namespace {

// Interior vertices and edges, where watertightness is at stake: a fan of
// seven triangles round a centre and a 4×4 grid of quads (two triangles
// each), both in a tilted plane beside the scene (nothing else in front of
// them for the rays aimed at them); a ray that crosses that plane through one
// of their vertices or edges must hit it there. Also a zero-area triangle, a
// point and a needle, and a square in the plane y = squareY, alone there:
// a ray in that plane must miss it, one crossing it at a small angle must hit
// it where it crosses. Rays through the boundary of a mesh (a wall's corner)
// touch it only up to rounding: there either answer is right, so they are not a class.
struct HardTriangles {
  std::vector<glm::vec3> vertices, edgePoints;  // interior ones
  glm::vec3 normal{0.0f};
  glm::vec3 squareLo{0.0f}, squareHi{0.0f};  // y equal: the square's plane
};
FlatScene withHardTriangles(FlatScene s, HardTriangles* hard = nullptr) {
  auto add = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    s.positions.insert(s.positions.end(), {a, b, c});
    s.normals.insert(s.normals.end(), 3, glm::vec3(0, 0, 1));
    s.uvs.insert(s.uvs.end(), 3, glm::vec2(0));
    s.material.push_back(0);
    s.meshOfTriangle.push_back(0);
  };
  const glm::vec3 e1 = glm::normalize(glm::vec3(1.0f, 0.2f, 0.3f));
  const glm::vec3 e2 = glm::normalize(glm::cross(glm::vec3(0.1f, 0.3f, 1.0f), e1));
  HardTriangles h;
  h.normal = glm::normalize(glm::cross(e1, e2));
  glm::vec3 off(0.0f);  // beside the scene, by more than the aimed rays' length
  for (auto& p : s.positions) off = glm::max(off, p + glm::vec3(0.6f, 0.0f, 0.0f));
  off = glm::vec3(off.x, 0.0f, 0.0f);
  const glm::vec3 centre = off + glm::vec3(0.31f, 0.27f, 0.4f);
  const int n = 7;
  auto rim = [&](int k) {
    const float a = 6.2831853f * float(k % n) / n;
    return centre + 0.1f * (std::cos(a) * e1 + std::sin(a) * e2);
  };
  for (int k = 0; k < n; ++k) {
    add(centre, rim(k), rim(k + 1));
    h.edgePoints.push_back(0.5f * (centre + rim(k)));
  }
  h.vertices.push_back(centre);
  const glm::vec3 corner = centre + 0.15f * e1 - 0.1f * e2;  // the fan's plane, beside it
  auto at = [&](int i, int j) { return corner + 0.05f * (float(i) * e1 + float(j) * e2); };
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      add(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      add(at(i, j), at(i + 1, j + 1), at(i, j + 1));
      h.edgePoints.push_back(0.5f * (at(i, j) + at(i + 1, j + 1)));  // the quad's diagonal
      if (i > 0) h.edgePoints.push_back(0.5f * (at(i, j) + at(i, j + 1)));
      if (j > 0) h.edgePoints.push_back(0.5f * (at(i, j) + at(i + 1, j)));
      if (i > 0 && j > 0) h.vertices.push_back(at(i, j));
    }
  // The square, 0.8 below everything else.
  h.squareLo = off + glm::vec3(0.0f, -0.8f, 0.0f);
  h.squareHi = off + glm::vec3(0.3f, -0.8f, 0.3f);
  const glm::vec3 q0 = h.squareLo, q2 = h.squareHi, q1(q2.x, q0.y, q0.z), q3(q0.x, q0.y, q2.z);
  add(q0, q1, q2);
  add(q0, q2, q3);
  // Zero area, exactly: collinear along x, and a point; a needle. Far below.
  const glm::vec3 low = off + glm::vec3(0.0f, -2.0f, 0.0f);
  add(low + glm::vec3(0.1f, 0.0f, 0.0f), low + glm::vec3(0.2f, 0.0f, 0.0f),
      low + glm::vec3(0.3f, 0.0f, 0.0f));
  add(low + glm::vec3(0.5f, 0.1f, 0.2f), low + glm::vec3(0.5f, 0.1f, 0.2f),
      low + glm::vec3(0.5f, 0.1f, 0.2f));
  add(low + glm::vec3(0.2f, 0.5f, 0.3f), low + glm::vec3(0.4f, 0.5f, 0.3f),
      low + glm::vec3(0.3f, 0.5f + 1e-6f, 0.3f));
  if (hard) *hard = h;
  return s;
}

glm::vec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<float> g;
  glm::vec3 d(g(rng), g(rng), g(rng));
  return glm::length(d) > 0.0f ? glm::normalize(d) : glm::vec3(0, 0, 1);
}

struct RaySet {
  std::string name;
  std::vector<TraceRay> rays;
};

// The ray classes; `embree` gives the distances the "ends on a surface" rays end at.
std::vector<RaySet> hardRays(const FlatScene& s, const HardTriangles& hard, const EmbreeTracer& embree,
                             size_t perClass, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (auto& p : s.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::vec3 size = hi - lo;
  const float diag = glm::length(size);
  auto inBox = [&](float margin) {
    return lo - margin * size + (1.0f + 2.0f * margin) * glm::vec3(u01(rng), u01(rng), u01(rng)) * size;
  };
  std::vector<size_t> solid;  // triangles of positive area (the zero-area ones are no surface)
  for (size_t t = 0; t < s.triangleCount(); ++t)
    if (glm::cross(s.positions[3 * t + 1] - s.positions[3 * t],
                   s.positions[3 * t + 2] - s.positions[3 * t]) != glm::vec3(0.0f))
      solid.push_back(t);
  auto triangle = [&] { return solid[size_t(u01(rng) * float(solid.size())) % solid.size()]; };
  // Through `target` on the hard triangles' plane, from the side of its normal at 20–90° to the plane.
  auto aimed = [&](glm::vec3 target) {
    glm::vec3 d = randomUnit(rng);
    if (glm::dot(d, hard.normal) > -0.35f)
      d = glm::normalize(d - (glm::dot(d, hard.normal) + 1.0f) * hard.normal);
    TraceRay r;
    const float dist = 0.02f + 0.3f * u01(rng);
    r.origin = target - dist * d;
    r.dir = glm::normalize(target - r.origin);
    r.tmax = u01(rng) < 0.5f ? 2.0f * dist : std::numeric_limits<float>::infinity();
    r.pad = glm::length(target - r.origin);  // (the test's own field: where the hit must be)
    return r;
  };
  std::vector<RaySet> sets = {{"random", {}},        {"vertices", {}},     {"edges", {}},
                              {"grazing", {}},       {"on a surface", {}}, {"ends on a surface", {}},
                              {"axis-parallel", {}}, {"in a plane", {}}};
  for (size_t i = 0; i < perClass; ++i) {
    TraceRay r;
    r.origin = inBox(0.1f);
    r.dir = randomUnit(rng);
    r.tmax = u01(rng) < 0.3f ? std::numeric_limits<float>::infinity() : u01(rng) * diag;
    sets[0].rays.push_back(r);
    const size_t t = triangle();
    const glm::vec3 a = s.positions[3 * t], b = s.positions[3 * t + 1], c = s.positions[3 * t + 2];
    sets[1].rays.push_back(aimed(hard.vertices[i % hard.vertices.size()]));
    sets[2].rays.push_back(aimed(hard.edgePoints[i % hard.edgePoints.size()]));
    // At 0.6° to 6° to the square, through a point of it: the hit is there; rounding moves it
    // by about the coordinates' rounding over the sine of that angle (in pad, the tolerance's factor).
    const glm::vec3 target(hard.squareLo.x + (0.05f + 0.9f * u01(rng)) * (hard.squareHi.x - hard.squareLo.x),
                           hard.squareLo.y,
                           hard.squareLo.z + (0.05f + 0.9f * u01(rng)) * (hard.squareHi.z - hard.squareLo.z));
    const float theta = 0.01f + 0.09f * u01(rng), phi = 6.2831853f * u01(rng);
    TraceRay g;
    g.dir = glm::vec3(std::cos(theta) * std::cos(phi), -std::sin(theta), std::cos(theta) * std::sin(phi));
    const float gd = 0.05f + 0.2f * u01(rng);
    g.origin = target - gd * g.dir;
    g.tmax = 2.0f * gd;
    g.pad = 1.0f / std::sin(theta);
    sets[3].rays.push_back(g);
    // Exactly in the square's plane, across it: no hit.
    TraceRay p2;
    p2.dir = glm::vec3(std::cos(phi), 0.0f, std::sin(phi));
    p2.origin = target - 0.4f * p2.dir;
    p2.origin.y = hard.squareLo.y;
    p2.tmax = 0.8f;
    sets[7].rays.push_back(p2);
    // From a point of the triangle (as rounded), in any direction.
    TraceRay o;
    const float x = u01(rng), y = u01(rng) * (1.0f - x);
    o.origin = a + x * (b - a) + y * (c - a);
    o.dir = randomUnit(rng);
    o.tmax = diag;
    sets[4].rays.push_back(o);
    // tmax exactly at Embree's hit distance.
    TraceRay h = r;
    const TriangleHit eh = embree.firstHit(h.origin, h.dir, 0.0f, 2.0f * diag);
    h.tmax = eh.hit ? eh.t : diag;
    sets[5].rays.push_back(h);
    TraceRay p;
    p.origin = inBox(0.05f);
    p.dir = glm::vec3(0.0f);
    p.dir[int(i % 3)] = i % 2 ? 1.0f : -1.0f;
    p.tmax = diag;
    sets[6].rays.push_back(p);
  }
  return sets;
}

}  // namespace

// Hit or miss as Embree says, and the same distance (relative 1e-5), on every
// class; starting on a surface, hits within 1e-4 of the scene's diagonal may
// go either way in both (the origin is the surface only up to rounding), and are counted apart.
TEST(Bvh, CppEqualsEmbreeOnAMillionRaysWithHardCases) {
  std::vector<std::string> scenes = {"builtin:cornell"};
  const std::string original = test::sharedScene("cornell-box/CornellBox-Original.obj");
  if (!original.empty()) scenes.push_back(original);
  size_t total = 0, hits = 0;
  // Both layouts: binary (Aila & Laine) and 4-wide; the second scene in the other width.
  for (size_t si = 0; si < 2 * scenes.size(); ++si) {
    const std::string& name = scenes[si % scenes.size()];
    BvhBuildOptions options;
    options.width = si < scenes.size() ? 2u : 4u;
    SCOPED_TRACE(name + ", width " + std::to_string(options.width));
    HardTriangles hard;
    const FlatScene s = withHardTriangles(flatten(loadScene(name), 0.0f), &hard);
    const BvhArrays bvh = buildBvh(s, options);
    EXPECT_EQ(bvh.dropped, 2u);  // the line and the point of withHardTriangles
    EXPECT_EQ(bvh.tris.size(), 3 * (s.triangleCount() - 2));
    EXPECT_LE(bvh.depth, shared::bvhMaxDepth(options.width));
    const EmbreeTracer embree(s);
    float diag = 0.0f;
    {
      glm::vec3 lo(1e30f), hi(-1e30f);
      for (auto& p : s.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
      diag = glm::length(hi - lo);
    }
    for (const RaySet& set : hardRays(s, hard, embree, 1000000 / (8 * scenes.size()) + 1, 17)) {
      size_t mismatches = 0, nearOrigin = 0, atTmax = 0, embreeLeaks = 0;
      const bool watertight = set.name == "vertices" || set.name == "edges";
      std::string first;
      for (const TraceRay& r : set.rays) {
        const shared::BvhHit b = traceBvhCpu(bvh, r.origin, r.dir, r.tmax, false);
        const TriangleHit e = embree.firstHit(r.origin, r.dir, 0.0f, r.tmax);
        const bool any = traceBvhCpu(bvh, r.origin, r.dir, r.tmax, true).hit != 0u;
        ++total;
        hits += e.hit;
        // Relative 1e-5, with a floor of 1e-6 of the scene's diagonal (the coordinates' own rounding).
        const float tol = 1e-5f * std::max(e.t, 0.1f * diag);
        bool same = (b.hit != 0u) == e.hit && any == e.hit && (!e.hit || std::abs(b.t - e.t) <= tol);
        if (set.name == "grazing")  // the known answer, its rounding grown by 1 / sin(angle)
          same = b.hit && any && std::abs(b.t - 0.5f * r.tmax) <= tol * r.pad &&
                 (!e.hit || std::abs(b.t - e.t) <= tol * r.pad);
        if (set.name == "in a plane") same = !b.hit && !any && !e.hit;
        if (watertight) {
          // The known answer: the hit at the aimed vertex or edge. Embree's robust mode is not
          // watertight there (it misses some and goes on to what lies behind: counted, not failed).
          same = b.hit && any && std::abs(b.t - r.pad) <= tol;
          embreeLeaks += !e.hit || std::abs(e.t - r.pad) > tol;
        }
        if (!same && set.name == "on a surface" &&
            std::min(b.hit ? b.t : 1e30f, e.hit ? e.t : 1e30f) < 1e-4f * diag) {
          ++nearOrigin;  // the origin is on the surface only up to rounding: either answer is right
          continue;
        }
        if (set.name == "ends on a surface" && b.hit == 0u && e.hit && e.t == r.tmax) {
          // Embree's distance 1 ulp short of ours: the end is on the surface up to rounding. Ours
          // then hits at its own distance, and again with tmax exactly that distance.
          ++atTmax;
          const shared::BvhHit own = traceBvhCpu(bvh, r.origin, r.dir, 2.0f * r.tmax, false);
          const shared::BvhHit end = traceBvhCpu(bvh, r.origin, r.dir, own.t, false);
          same = own.hit && std::abs(own.t - e.t) <= tol && end.hit && end.t == own.t;
        }
        if (!same && mismatches++ == 0) {
          std::ostringstream o;
          o.precision(9);
          o << "o=(" << r.origin.x << "," << r.origin.y << "," << r.origin.z << ") d=(" << r.dir.x << ","
            << r.dir.y << "," << r.dir.z << ") tmax " << r.tmax << ": bvh " << b.hit << " t " << b.t
            << " (any " << any << "), embree " << e.hit << " t " << e.t;
          first = o.str();
        }
      }
      EXPECT_EQ(mismatches, 0u) << name << ", " << set.name << " (" << set.rays.size() << " rays; "
                                << nearOrigin << " within 1e-4 of the origin, " << atTmax
                                << " ending 1 ulp short): " << first;
      if (watertight)
        std::printf("[ info ] %s, %s: Embree (robust) missed %zu of %zu rays through interior %s\n",
                    name.c_str(), set.name.c_str(), embreeLeaks, set.rays.size(), set.name.c_str());
    }
  }
  EXPECT_GE(total, 1000000u);
  EXPECT_GT(hits, total / 4);  // the classes are not mostly misses
}

// Scenes at the builder's edges: none, one triangle (the root is a leaf), and
// only degenerate triangles (each is kept and never hit).
TEST(Bvh, EmptyOneTriangleAndDegenerateScenesTrace) {
  FlatScene empty;
  BvhArrays e = buildBvh(empty);
  EXPECT_EQ(traceBvhCpu(e, glm::vec3(0), glm::vec3(0, 0, 1), 10.0f, false).hit, 0u);
  FlatScene one;
  one.positions = {glm::vec3(0.0f, 0.0f, 0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f)};
  one.normals.assign(3, glm::vec3(0, 0, 1));
  one.uvs.assign(3, glm::vec2(0));
  one.material = {0};
  one.meshOfTriangle = {0};
  BvhArrays b = buildBvh(one);
  const glm::vec3 c = (one.positions[0] + one.positions[1] + one.positions[2]) / 3.0f;
  const shared::BvhHit h = traceBvhCpu(b, c + glm::vec3(0.0f, 0.0f, 1.0f), glm::vec3(0, 0, -1), 10.0f, false);
  EXPECT_EQ(h.hit, 1u);
  EXPECT_EQ(h.triangle, 0u);
  EXPECT_EQ(h.t, 1.0f);
  EXPECT_NEAR(h.u, 1.0f / 3.0f, 1e-6f);
  EXPECT_NEAR(h.v, 1.0f / 3.0f, 1e-6f);
  // In the triangle's plane: no hit; ending exactly on it: a hit.
  EXPECT_EQ(traceBvhCpu(b, glm::vec3(-1.0f, 0.25f, 0.0f), glm::vec3(1, 0, 0), 10.0f, false).hit, 0u);
  EXPECT_EQ(traceBvhCpu(b, c + glm::vec3(0.0f, 0.0f, 1.0f), glm::vec3(0, 0, -1), 1.0f, false).hit, 1u);
  FlatScene flat;  // a line and a point: zero area
  flat.positions = {glm::vec3(0.1f), glm::vec3(0.2f), glm::vec3(0.3f),
                    glm::vec3(0.5f), glm::vec3(0.5f), glm::vec3(0.5f)};
  flat.normals.assign(6, glm::vec3(0, 0, 1));
  flat.uvs.assign(6, glm::vec2(0));
  flat.material.assign(2, 0);
  flat.meshOfTriangle.assign(2, 0);
  BvhArrays d = buildBvh(flat);
  EXPECT_EQ(d.dropped, 2u);
  std::mt19937 rng(3);
  for (int i = 0; i < 1000; ++i)
    EXPECT_EQ(traceBvhCpu(d, glm::vec3(0.2f), randomUnit(rng), 10.0f, false).hit, 0u);
  // Non-finite input is a miss, not a trap.
  const float nan = std::nanf("");
  EXPECT_EQ(traceBvhCpu(b, glm::vec3(nan), glm::vec3(0, 0, -1), 10.0f, false).hit, 0u);
  EXPECT_EQ(traceBvhCpu(b, c, glm::vec3(0, 0, -1), -1.0f, false).hit, 0u);
  EXPECT_EQ(traceBvhCpu(b, c, glm::vec3(0), 1.0f, false).hit, 0u);
}

// The GLSL build on llvmpipe equals the C++ build bit for bit: hit, t's bits,
// nodes visited, and the grid cell that holds the hit point.
TEST(Bvh, GlslOnLlvmpipeEqualsCppBitForBit) {
  auto gl = GlContext::create();
  ShaderLibrary shaders;
  Profiler profiler(true);
  const Scene scene = loadScene("builtin:cornell");
  HardTriangles hard;
  const FlatScene s = withHardTriangles(flatten(scene, 0.0f), &hard);
  for (unsigned width : {2u, 4u}) {
    SCOPED_TRACE("width " + std::to_string(width));
    BvhBuildOptions options;
    options.width = width;
    const BvhArrays bvh = buildBvh(s, options);
    const EmbreeTracer embree(s);
    GridBox box = fitGridBox(scene, glm::uvec3(64, 64, 128), 0.0f);
    OrMipPyramid pyramid{BinaryGrid(box)};
    GlPyramid gpuPyramid(pyramid);
    GpuBvh gpu(bvh);
    std::vector<TraceRay> rays;
    for (const RaySet& set : hardRays(s, hard, embree, 12000, 29))
      rays.insert(rays.end(), set.rays.begin(), set.rays.end());
    TracerInputs in;
    in.bvh = &bvh;
    in.pyramid = &pyramid;
    std::vector<TraceResult> cpu;
    createTracer("bvh", in)->traceBatch(rays, cpu);
    const std::vector<TraceResult> glsl = traceRaysGl(gpuPyramid, shaders, "bvh", rays, profiler, 0, &gpu);
    size_t mismatches = 0, hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      hits += cpu[i].hit;
      if (cpu[i].hit != glsl[i].hit || cpu[i].steps != glsl[i].steps ||
          (cpu[i].hit && (cpu[i].t != glsl[i].t || cpu[i].voxel != glsl[i].voxel))) {
        if (mismatches++ == 0)
          ADD_FAILURE() << "ray " << i << ": hit " << cpu[i].hit << "/" << glsl[i].hit << " t " << cpu[i].t
                        << "/" << glsl[i].t << " steps " << cpu[i].steps << "/" << glsl[i].steps;
      }
    }
    EXPECT_EQ(mismatches, 0u) << "of " << rays.size();
    EXPECT_GT(hits, rays.size() / 4);
  }
  EXPECT_EQ(gl->errorCount(), 0);
}

}  // namespace vgi
