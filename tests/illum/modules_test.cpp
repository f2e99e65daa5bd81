// Registry-driven tests of the module framework: every method of the table,
// with its default parameters and with each non-default value of its choice
// parameters, builds exactly what its declared needs name, and every program
// those renders compose passes the Khronos reference compiler; the sample loop's
// accumulation, checkpoints and sample passes; checked uniforms and bindings.
#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "core/error.h"
#include "core/gl_context.h"
#include "core/image_metrics.h"
#include "core/params.h"
#include "core/scene_loader.h"
#include "core/shader_library.h"
#include "illum/framework/sample_loop.h"
#include "illum/resources/kinds.h"
#include "illum/run/render_job.h"
#include "render_util.h"
#include "test_util.h"
#include "traverse/ray_tracers.h"

namespace vgi {

namespace {
// The choice parameters (a|b|c, bool) a method read with these settings, with their values.
std::vector<std::pair<std::string, std::vector<std::string>>> choiceParams(const ParamSet& p) {
  std::vector<std::pair<std::string, std::vector<std::string>>> out;
  const nlohmann::json resolved = p.resolved();
  for (auto& d : p.docs()) {
    if (!resolved.contains(d.key)) continue;
    std::vector<std::string> values;
    if (d.type == "bool")
      values = {"true", "false"};
    else if (d.type.find('|') != std::string::npos) {
      size_t s = 0;
      for (size_t bar; (bar = d.type.find('|', s)) != std::string::npos; s = bar + 1)
        values.push_back(d.type.substr(s, bar - s));
      values.push_back(d.type.substr(s));
    }
    if (!values.empty()) out.push_back({d.key, values});
  }
  return out;
}

// Default settings, each non-default choice, and (one level deeper) each
// non-default choice of a parameter that only those settings made apply
// (reference integrator=nearfield → visibility=voxels).
std::vector<std::vector<std::string>> configurations(const MethodInfo& info, const Scene& scene) {
  std::vector<std::vector<std::string>> configs = {{}};
  ParamSet base;
  info.create(base, scene);
  const nlohmann::json baseResolved = base.resolved();  // items() must not outlive its object
  std::vector<std::string> baseKeys;
  for (auto& [k, v] : baseResolved.items()) baseKeys.push_back(k);
  for (auto& [key, values] : choiceParams(base))
    for (auto& v : values) {
      if (v == baseResolved[key].dump() || "\"" + v + "\"" == baseResolved[key].dump()) continue;
      std::vector<std::string> c = {key + "=" + v};
      ParamSet p;
      for (auto& kv : c) p.setFromString(kv);
      info.create(p, scene);
      configs.push_back(c);
      for (auto& [key2, values2] : choiceParams(p)) {
        if (std::find(baseKeys.begin(), baseKeys.end(), key2) != baseKeys.end()) continue;
        for (auto& v2 : values2) {
          const std::string def2 = p.resolved()[key2].dump();
          if (v2 == def2 || "\"" + v2 + "\"" == def2) continue;
          configs.push_back({c[0], key2 + "=" + v2});
        }
      }
    }
  return configs;
}
}  // namespace

// The programs ShaderLibrary wrote into `dir` ($VGI_SHADER_DUMP), each program's stages (one digest)
// compiled and linked by the Khronos reference compiler, glslangValidator, under GLSL 4.50's rules —
// what NVIDIA's and AMD's compilers hold a program to where Mesa's front end is more lenient.
struct GlslangReport {
  int programs = 0;
  std::vector<std::string> failures, warnings;
};
GlslangReport runGlslang(const std::string& dir) {
  std::map<std::string, std::vector<std::string>> programs;  // digest → stage files
  for (auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    const size_t last = name.find_last_of('.'), prev = name.find_last_of('.', last - 1);
    programs[name.substr(prev + 1, last - prev - 1)].push_back(e.path().string());
  }
  GlslangReport r;
  for (auto& [digest, files] : programs) {
    std::string cmd = "glslangValidator -l";
    for (auto& f : files) cmd += " '" + f + "'";
    FILE* p = popen((cmd + " 2>&1").c_str(), "r");
    if (!p) fail("cannot run ", cmd);
    std::string log;
    char buf[512];
    while (fgets(buf, sizeof buf, p)) log += buf;
    const int rc = pclose(p);
    ++r.programs;
    if (rc != 0) r.failures.push_back(cmd + ":\n" + log);
    if (log.find("WARNING") != std::string::npos) r.warnings.push_back(cmd + ":\n" + log);
  }
  return r;
}

// The framework reads each need's kind from the need (ResourceNeed::kindRow); the kinds table lists
// every row once, by its name, and every need any method declares (at its defaults) is one of them.
TEST(ResourceKinds, EveryNeedOfEveryMethodIsARowOfTheTable) {
  std::set<std::string> names;
  for (const ResourceKind* k : resourceKinds()) {
    EXPECT_TRUE(names.insert(k->name).second) << k->name << " twice";
    EXPECT_FALSE(k->description.empty()) << k->name;
  }
  const Scene scene = loadScene("builtin:cornell");
  int needs = 0;
  for (const MethodInfo& info : methodRegistry()) {
    ParamSet p;
    const std::unique_ptr<Method> m = info.create(p, scene);
    for (const ResourceNeed& n : m->needs().closure()) {
      ++needs;
      EXPECT_EQ(n.kindRow().name, n.kind()) << info.name;
      EXPECT_NE(std::find(resourceKinds().begin(), resourceKinds().end(), &n.kindRow()),
                resourceKinds().end())
          << info.name << ": " << n.kind() << " is not in illum/resources/kinds.cpp";
    }
  }
  EXPECT_GT(needs, 20);
}

TEST(Modules, EveryMethodBuildsExactlyWhatItsNeedsDeclareAndPassesGlslang) {
  ASSERT_EQ(std::system("glslangValidator --version > /dev/null 2>&1"), 0)
      << "glslangValidator is missing: install glslang-tools (scripts/setup.sh does)";
  const std::string dump = testing::TempDir() + "/vgi_glslang_dump";
  std::filesystem::remove_all(dump);
  setenv("VGI_SHADER_DUMP", dump.c_str(), 1);
  const Scene scene = loadScene("builtin:cornell");
  int renders = 0;
  for (const MethodInfo& info : methodRegistry()) {
    for (auto& config : configurations(info, scene)) {
      std::vector<std::string> set = config;
      if (info.needsGl) set.push_back("voxels=32");  // small grids: the names, not the images, are tested
      ParamSet p;
      for (auto& kv : set) {
        try {
          p.setFromString(kv);
        } catch (const Error&) {
        }
      }
      std::vector<std::string> names;
      try {
        names = info.create(p, scene)->needs().names();
        p.checkAllUsed(info.name);
      } catch (const Error&) {
        set = config;  // the method has no `voxels`
        ParamSet q;
        for (auto& kv : set) q.setFromString(kv);
        names = info.create(q, scene)->needs().names();
      }
      RenderOutput out = test::render("builtin:cornell", info.name, set, 8, 2);
      std::vector<std::string> built = out.stats["built"];
      EXPECT_EQ(built, names) << info.name << " " << nlohmann::json(set).dump();
      EXPECT_EQ(out.stats["needs"].get<std::vector<std::string>>(), names);
      // The per-sample passes are timed passes, include the accumulation, and no set-up pass.
      const nlohmann::json timings = out.stats["timings_ms"];
      std::vector<std::string> passes = out.stats["sample_passes"];
      EXPECT_NE(std::find(passes.begin(), passes.end(), "accumulate"), passes.end()) << info.name;
      for (auto& pass : passes) {
        EXPECT_TRUE(timings.contains(pass)) << pass;
        for (const char* setup :
             {"rsm", "light_maps", "upload", "build_bvh", "pyramid", "atlas_render", "readback"})
          EXPECT_NE(pass, setup) << info.name;
      }
      ++renders;
    }
  }
  EXPECT_GE(renders, 20);  // the configurations were really enumerated
  {
    // What no render composes: the viewer's display, the bench's ray kernel for each GLSL tracer.
    auto ctx = GlContext::create();
    ShaderLibrary shaders;
    shaders.program({"apps/view_display.vert.glsl", "apps/view_display.frag.glsl"});
    for (const TracerInfo& t : tracerRegistry()) {
      if (!t.glsl) continue;
      ShaderDefines d = {{"VGI_TRACER", std::to_string(t.define)}, {"BVH_WIDTH", "2u"}};
      shaders.program({"traverse/trace_rays.comp.glsl"}, d);
      d["TRACE_FROM_LEVEL"] = "1";
      shaders.program({"traverse/trace_rays.comp.glsl"}, d);
    }
  }
  unsetenv("VGI_SHADER_DUMP");
  const GlslangReport g = runGlslang(dump);
  EXPECT_GE(g.programs, 60);  // every method's permutations, the voxelizers, the tracers, the viewer
  for (auto& f : g.failures) ADD_FAILURE() << f;
  // No warning remains either (glslang 12 on every program, December 2026).
  for (auto& w : g.warnings) ADD_FAILURE() << "warning: " << w;
  std::printf("glslangValidator: %d programs, %zu failed, %zu with warnings\n", g.programs, g.failures.size(),
              g.warnings.size());
}

// Kahan summation on the GPU: 10^5 samples of 0.3 average to 0.3 within a
// few ulp; one float add per sample drifts (this is what makes the test able to fail).
TEST(SampleLoop, CompensatedAccumulationDoesNotDriftOver1e5Samples) {
  auto ctx = GlContext::create();
  ShaderLibrary shaders;
  const int n = 100000;
  const float value = 0.3f;
  double error[2];
  for (int mode = 0; mode < 2; ++mode) {
    GlFilm film(4, 4, {"image"}, shaders);
    const float v[4] = {value, value, value, 1.0f};
    glClearTexImage(film.sampleImage("image"), 0, GL_RGBA, GL_FLOAT, v);
    for (int i = 0; i < n; ++i) film.accumulate(mode == 0 ? Accumulation::Compensated : Accumulation::Plain);
    Image img = film.read("image", n);
    error[mode] = std::abs(double(img.pixels[5].x) - double(value)) / double(value);
  }
  EXPECT_LT(error[0], 1e-6) << "compensated";
  EXPECT_GT(error[1], 1e-5) << "plain float sums should drift here";
  EXPECT_EQ(ctx->errorCount(), 0);
}

TEST(SampleLoop, CheckpointsWriteTheImageSoFarAtThoseSampleCounts) {
  RenderOptions o;
  o.method = "direct";
  o.width = o.height = 8;
  o.spp = 8;
  o.progress = false;
  o.checkpoints = {1, 4};
  std::vector<int> seen;
  RenderOutput last = runRender(o, {}, [&](int spp, const RenderOutput& c) {
    seen.push_back(spp);
    EXPECT_EQ(c.stats["spp_completed"].get<int>(), spp);
    EXPECT_TRUE(c.stats["checkpoint"].get<bool>());
    EXPECT_EQ(c.result.image.width, 8);
  });
  EXPECT_EQ(seen, (std::vector<int>{1, 4}));
  EXPECT_EQ(last.result.sppCompleted, 8);
  o.checkpoints = {9};
  test::expectError([&] { runRender(o); }, {"--checkpoints", "9"});
}

TEST(ShaderLibrary, AnUnknownUniformIsAnErrorNamingProgramAndUniform) {
  auto ctx = GlContext::create();
  ShaderLibrary shaders;
  unsigned prog = shaders.program({"illum/accumulate.comp.glsl"});
  shaders.setUniform(prog, "uCompensated", 1);
  test::expectError([&] { shaders.setUniform(prog, "uCompensatd", 1); },
                    {"uCompensatd", "illum/accumulate.comp.glsl"});
  EXPECT_EQ(ShaderLibrary::declaredUniforms(
                "uniform int a, b[2];\nlayout(binding = 0) uniform sampler2D s;\n"
                "uniform Block { int x; } blk; // uniform float c;\n/* uniform int d; */"),
            (std::set<std::string>{"a", "b", "s"}));
}

TEST(ShaderLibrary, TwoResourcesOfAProgramOnOneUnitAreAnError) {
  auto ctx = GlContext::create();
  const std::string root = testing::TempDir() + "/vgi_bindings_shaders";
  std::filesystem::create_directories(root);
  std::ofstream(root + "/clash.comp.glsl") << "layout(local_size_x = 1) in;\n"
                                              "layout(std430, binding = 4) buffer A { uint a[]; };\n"
                                              "layout(std430, binding = 4) buffer B { uint b[]; };\n"
                                              "void main() { a[0] = b[0] + 1u; }\n";
  ShaderLibrary shaders(root);
  test::expectError([&] { shaders.program({"clash.comp.glsl"}); }, {"clash.comp.glsl", "unit 4", "A", "B"});
}

namespace {
// The AO scenes of the two tests below in TempDir()/name: planes.json (a 4 m
// floor and a parallel plane 0.5 above it) and floor.json (the floor alone),
// seen from 0.25 above the floor's centre, looking down.
std::string writeAoPlaneScenes(const std::string& name) {
  const std::string dir = testing::TempDir() + "/" + name;
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/planes.obj") << "v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\n"
                                        "v -2 0.5 -2\nv 2 0.5 -2\nv 2 0.5 2\nv -2 0.5 2\n"
                                        "f 1 2 3\nf 1 3 4\nf 5 7 6\nf 5 8 7\n";
  std::ofstream(dir + "/floor.obj") << "v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\nf 1 2 3\nf 1 3 4\n";
  for (const char* mesh : {"planes", "floor"})
    std::ofstream(dir + "/" + mesh + ".json") << "{\"meshes\": [{\"path\": \"" << mesh << ".obj\"}],\n"
                                              << "\"camera\": {\"position\": [0, 0.25, 0], \"target\": [0, "
                                                 "0, 0.001], \"up\": [0, 0, 1], \"fov_deg\": 20}}\n";
  return dir;
}
}  // namespace

// Analytic AO: a point under a parallel plane at height h, cosine rays of
// length r: AO = min(1, (h/r)^2); with nothing above, AO = 1. voxel_ao and
// its exact counterpart both.
TEST(Modules, AoUnderAParallelPlaneIsHOverRSquared) {
  const std::string dir = writeAoPlaneScenes("vgi_ao_planes");
  const float expected[2] = {0.25f, 1.0f};  // (0.5 / 1)^2; unoccluded
  for (int s = 0; s < 2; ++s) {
    const std::string scene = dir + "/" + (s == 0 ? "planes" : "floor") + ".json";
    for (const char* method : {"voxel_ao", "reference"}) {
      std::vector<std::string> set = {"radius=1"};
      if (std::string(method) == "reference")
        set.push_back("integrator=ao");
      else
        set.push_back("voxels=128x128x128");
      RenderOutput out = test::render(scene, method, set, 16, 64);
      double mean = 0;
      for (auto& p : out.result.image.pixels) mean += p.x;
      mean /= double(out.result.image.pixels.size());
      EXPECT_NEAR(mean, expected[s], s == 0 ? 0.03 : 1e-6) << method << " " << scene;
    }
  }
}

// vct_ao under the same parallel plane (cubic cells, anisotropic chain,
// receiver guard) and on the open floor alone. Under the plane the cones see
// most but not all of the occlusion (measured 0.417 against 0.25): trilinear
// filtering spreads a one-voxel wall over two texels of optical depth 2, so a
// cone crossing it keeps e^-2 of its light, and the 8-cone ring's axes at 60°
// meet the plane exactly at r; they must not over-occlude (> 0.2) and must see
// more than half of it (< 0.625). The open floor must not occlude itself (the
// guard): AO 1 for the default 8 cones (5 cones, whose 90° apertures reach
// below the horizon: 0.984; docs/BENCHMARKS.md).
TEST(Modules, VctAoUnderAParallelPlaneAndOnAnOpenFloor) {
  const std::string dir = writeAoPlaneScenes("vgi_vct_ao_planes");
  auto meanAo = [&](const char* mesh, const char* cones) {
    RenderOutput out =
        test::render(dir + "/" + mesh + ".json", "vct_ao", {"radius=1", "voxels=128", cones}, 16, 4);
    double mean = 0;
    for (auto& p : out.result.image.pixels) {
      EXPECT_TRUE(std::isfinite(p.x));
      mean += p.x;
    }
    return mean / double(out.result.image.pixels.size());
  };
  const double under = meanAo("planes", "cones=8");
  EXPECT_GT(under, 0.2);
  EXPECT_LT(under, 0.625);
  EXPECT_NEAR(meanAo("floor", "cones=8"), 1.0, 1e-4);
}

}  // namespace vgi

namespace vgi {
// `voxels`, the grid seen from the camera: in the Cornell box every pixel inside the opening sees a
// wall's voxels (no miss), the side walls show x faces (red), the floor and ceiling y faces (green), the back wall a z
// face (blue), where they are in the image (rows top-down), and the hierarchical tracer and the DDA
// see the same voxels.
TEST(Modules, VoxelViewShowsTheGridsFacesWhereTheWallsAre) {
  const RenderOutput h = test::render("builtin:cornell", "voxels", {"voxels=64x64x128"}, 48, 1);
  const Image& img = h.result.image;
  int misses = 0;  // inside the box's opening (the image's border sees past the box)
  for (int y = 6; y < 42; ++y)
    for (int x = 6; x < 42; ++x) misses += img.at(x, y).x + img.at(x, y).y + img.at(x, y).z <= 0.0f;
  EXPECT_EQ(misses, 0);
  auto dominant = [&](int x, int y) {
    const glm::vec3 c = img.at(x, y);
    return c.x > c.y && c.x > c.z ? 0 : (c.y > c.z ? 1 : 2);
  };
  EXPECT_EQ(dominant(6, 24), 0) << "left wall";
  EXPECT_EQ(dominant(42, 24), 0) << "right wall";
  EXPECT_EQ(dominant(24, 4), 1) << "ceiling";
  EXPECT_EQ(dominant(12, 43), 1) << "floor";
  EXPECT_EQ(dominant(24, 14), 2) << "back wall";
  const RenderOutput d = test::render("builtin:cornell", "voxels", {"voxels=64x64x128", "tracer=dda"}, 48, 1);
  EXPECT_EQ(compareImages(img, d.result.image).relMae, 0.0);
}

// level = l shows OR-mip level l's columns as cells: conservative (every pixel that sees the grid sees
// the level), coarser (not the same picture), the same for the hierarchical tracer and the DDA, and a
// level the pyramid does not have is refused naming it.
TEST(Modules, VoxelViewOfAMipLevelIsConservative) {
  const RenderOutput fine = test::render("builtin:cornell", "voxels", {"voxels=64x64x128"}, 48, 1);
  const RenderOutput coarse =
      test::render("builtin:cornell", "voxels", {"voxels=64x64x128", "level=3"}, 48, 1);
  const RenderOutput dda =
      test::render("builtin:cornell", "voxels", {"voxels=64x64x128", "level=3", "tracer=dda"}, 48, 1);
  int fineHits = 0, lost = 0;
  for (size_t i = 0; i < fine.result.image.pixels.size(); ++i) {
    const bool f = fine.result.image.pixels[i] != glm::vec3(0.0f),
               c = coarse.result.image.pixels[i] != glm::vec3(0.0f);
    fineHits += f;
    lost += f && !c;
  }
  EXPECT_GT(fineHits, 48 * 48 / 2);
  EXPECT_EQ(lost, 0);
  EXPECT_GT(compareImages(fine.result.image, coarse.result.image).relMae, 0.05);
  EXPECT_EQ(compareImages(coarse.result.image, dda.result.image).relMae, 0.0);
  test::expectError(
      [&] {
        test::render("builtin:cornell", "voxels", {"voxels=64x64x128", "level=7"}, 8, 1);
      },
      {"level", "7", "64x64", "0 … 6"});
}

}  // namespace vgi

namespace vgi {

// tracer=bvh (illum/kits/tracer_kit.h): every voxel-tracing method runs with
// the scene's triangles on the GPU instead of the grid — the resource kind
// gpu_bvh built, the image finite — and it is exact visibility: voxel_ao with
// the BVH, no start offset to speak of and no passthrough, at full resolution
// unblurred, is the exact AO integral (reference integrator=ao, same radius)
// within noise; the voxel tracer at the same settings is not.
// An animation's binary grid, for a per-triangle voxelizer, is the static meshes' grid (voxelized once,
// kept) OR-ed with the dynamic meshes' of each frame: the grid view of the turning bunny's first frame
// equals the same pose as a still scene's (voxelized whole), pixel for pixel and cell for cell.
TEST(Modules, AnAnimationsKeptStaticGridIsTheWholeScenesGrid) {
  if (test::sharedScene("stanford-bunny/bun_zipper.ply").empty()) GTEST_SKIP() << "no Stanford bunny";
  const std::string scenes = std::string(VGI_TEST_DATA) + "/../../scenes/";
  for (const std::string v : {"conservative", "hybrid", "slicemap"}) {
    const RenderOptions o = test::options(scenes + "cornell-bunny.json", "voxels", {"voxelizer=" + v}, 48, 1);
    const test::Frames a = test::renderFrames(o, 2, 0.25f);
    const RenderOutput still =
        test::render(scenes + "cornell-bunny-still.json", "voxels", {"voxelizer=" + v}, 48, 1);
    EXPECT_EQ(a.images[0].pixels, still.result.image.pixels) << v;
    const nlohmann::json& frame = a.last.stats["frames"][0]["extra"]["grid"];
    EXPECT_GT(frame["voxels_set"].get<uint64_t>(), 10000u) << v;
    EXPECT_EQ(frame["voxels_set"], still.stats["extra"]["grid"]["voxels_set"]) << v;
    EXPECT_EQ(frame["stats"]["static_meshes"]["kept"], true) << v << ": " << frame.dump();
    EXPECT_GT(compareImages(a.images[0], a.images[1]).relMae, 0.001) << v << ": it moved";
  }
}

TEST(Modules, TracerBvhIsExactVisibilityForEveryVoxelTracingMethod) {
  for (const char* method : {"nearfield", "voxel_ao", "voxelpath", "vpl"}) {
    RenderOutput out = test::render("builtin:cornell", method, {"tracer=bvh"}, 16, 2);
    const std::vector<std::string> built = out.stats["built"];
    EXPECT_NE(std::find(built.begin(), built.end(), "gpu_bvh"), built.end()) << method;
    EXPECT_EQ(out.stats["extra"]["gpu_bvh"]["triangles"], 30) << method;
    EXPECT_EQ(out.stats["gl_errors"], 0) << method;
  }
  const std::string radius = "radius=0.0960740447";
  const std::vector<std::string> exactish = {"offset=0.01", "passthrough=false", "resolution=1", "blur=false",
                                             radius};
  const Image ref =
      test::render("builtin:cornell", "reference", {"integrator=ao", radius}, 48, 512).result.image;
  auto energy = [&](const char* tracer) {
    std::vector<std::string> set = exactish;
    set.push_back(std::string("tracer=") + tracer);
    return compareImages(test::render("builtin:cornell", "voxel_ao", set, 48, 32).result.image, ref)
        .energyRgb[0];
  };
  const double bvh = energy("bvh"), voxels = energy("hierarchical");
  // Measured: bvh 0.999 of the exact AO's energy (128², 16 spp); the voxels darker by their size.
  EXPECT_NEAR(bvh, 1.0, 0.01);
  EXPECT_GT(std::abs(voxels - 1.0), 2.0 * std::abs(bvh - 1.0)) << "voxels " << voxels << ", bvh " << bvh;
}

}  // namespace vgi

namespace vgi {

// Every int and float parameter of every method accepts both ends of its
// documented range (a float bound compared in double refused itself: vct's
// step=0.05), and a float beyond 32 bits is refused by name, not read as ∞.
TEST(Modules, EveryNumberParameterAcceptsBothEndsOfItsRange) {
  const Scene scene = loadScene("builtin:cornell");
  int checked = 0;
  for (const MethodInfo& info : methodRegistry()) {
    ParamSet defaults;
    info.create(defaults, scene);
    for (const ParamDoc& d : defaults.docs()) {
      if ((d.type != "float" && d.type != "int") || !(d.lo < d.hi)) continue;
      for (double bound : {d.lo, d.hi}) {
        char text[64];
        if (d.type == "float")
          std::snprintf(text, sizeof text, "%.9g", double(float(bound)));
        else
          std::snprintf(text, sizeof text, "%lld", (long long)bound);
        ParamSet p;
        p.setFromString(d.key + "=" + text);
        try {
          info.create(p, scene);
        } catch (const Error& e) {
          // Another check may refuse an extreme (memory, a combination): never the range itself.
          const std::string m = e.what();
          EXPECT_EQ(m.find("out of range"), std::string::npos)
              << info.name << " " << d.key << "=" << text << ": " << m;
        }
        ++checked;
      }
      if (d.type == "float") {
        ParamSet p;
        p.setFromString(d.key + "=1e300");
        test::expectError([&] { info.create(p, scene); }, {d.key, "1e300"});
      }
    }
  }
  EXPECT_GT(checked, 100);
}

// A cut-away camera ("near"): a grey quad at z = 0 hides an emissive quad at z = −1 (emission 2, facing
// the camera, the only light); with the near plane between them every device's primary visibility
// starts behind the grey quad and sees the emitter's exact radiance at the image centre, without it
// the grey quad's unlit front (0). The light transport still sees the grey quad: its shadow darkens
// nothing here, the emitter is seen directly.
TEST(CutAway, EveryDeviceSeesThroughTheNearPlane) {
  const std::string dir = testing::TempDir();
  std::ofstream(dir + "/cut_away.mtl") << "newmtl grey\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0 0 0\nKe 2 2 2\n";
  std::ofstream(dir + "/cut_away.obj") << "mtllib cut_away.mtl\n"
                                          "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                                          "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
                                          "usemtl grey\nf 1 2 3\nf 1 3 4\nusemtl lamp\nf 5 6 7\nf 5 7 8\n";
  for (const char* near : {"", R"(, "near": 2.5)"}) {
    const std::string scene = dir + "/cut_away" + (*near ? "_near" : "") + ".json";
    std::ofstream(scene) << R"({"meshes": [{"path": "cut_away.obj"}],
        "camera": {"position": [0, 0, 2], "target": [0, 0, 0], "fov_deg": 20)"
                         << near << "}}";
    for (const char* method : {"reference", "reference_gl", "direct", "nearfield"}) {
      const Image img = test::render(scene, method, {}, 16, 1).result.image;
      const glm::vec3 c = img.at(8, 8);
      if (*near)
        EXPECT_NEAR(c.x, 2.0f, 1e-5f) << method << ": the emitter behind the near plane";
      else
        EXPECT_LT(c.x, 1e-3f) << method << ": the grey quad's unlit front";
    }
  }
}

// The closed-mesh leak scene (scenes/leak-closed/, a sealed box seen through a cut-away camera): no
// light path enters the box, so both exact devices leave its inside exactly dark, and each one's
// leak against the other is only the pixels on the box's silhouette that one device's random
// sub-pixel positions saw from the inside only (falling with the samples: 1.7e-4 at 64, 1.2e-5 at
// 256), while the cone tracer's coarse cones carry the room's light through the walls (9 %).
TEST(LeakScenes, TheClosedBoxIsExactlyDarkForTheExactMethodsAndNotForCones) {
  const std::string scene = std::string(VGI_TEST_DATA) + "/../../scenes/leak-closed/closed-0.5v.json";
  const std::vector<std::string> path = {"integrator=path", "maxdepth=2"};
  const RenderOutput cpu = test::render(scene, "reference", path, 48, 64, {"indirect"});
  const RenderOutput gl = test::render(scene, "reference_gl", path, 48, 64, {"indirect"});
  const RenderOutput vct = test::render(scene, "vct", {}, 48, 1, {"indirect"});
  for (const char* ch : {"image", "indirect"}) {
    const auto img = [&](const RenderOutput& o) -> const Image& {
      return std::string(ch) == "image" ? o.result.image : o.result.aovs.at(ch);
    };
    size_t bothDark = 0;
    for (size_t i = 0; i < img(cpu).pixels.size(); ++i)
      bothDark += img(cpu).pixels[i] == glm::vec3(0.0f) && img(gl).pixels[i] == glm::vec3(0.0f);
    EXPECT_GT(double(bothDark) / double(img(cpu).pixels.size()), 0.25) << ch << ": the box's inside";
    EXPECT_LT(compareImages(img(gl), img(cpu)).leak, 2e-3) << ch;
    EXPECT_LT(compareImages(img(cpu), img(gl)).leak, 2e-3) << ch;
    EXPECT_GT(compareImages(img(vct), img(cpu)).leak, 0.02) << ch;
  }
}

}  // namespace vgi
