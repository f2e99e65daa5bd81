// The classes of bad input a fuzzer, the sanitizers and a new user found,
// each as the `vgi` command meets it: every case exits 0 with a finite image
// and valid stats, or 2 with a message naming the input — never a crash
// (-1 here), a hang, an internal error (3), or an exit 0 without its files.
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

#include "apps/cli_util.h"
#include "core/image.h"
#include "illum/framework/render_job.h"

namespace vgi {
using test::CliRun;
using test::dataPath;
using test::tmp;
using test::vgi;

namespace {
// A render of a corpus file at a small size.
CliRun renderBad(const std::string& file, const std::string& extra = "") {
  return vgi("render --scene '" + dataPath("bad/" + file) + "' --size 16x16 --spp 1 --quiet " + extra +
             " -o " + tmp("bad_" + file + ".exr"));
}
void expectRefused(const CliRun& r, std::initializer_list<std::string> needles) {
  EXPECT_EQ(r.code, 2) << r.output;
  for (auto& n : needles)
    EXPECT_NE(r.output.find(n), std::string::npos) << "'" << n << "' not in: " << r.output;
  EXPECT_EQ(r.output.find("internal error"), std::string::npos) << r.output;
}
// Exit 0, a finite image and stats that parse.
void expectRendered(const CliRun& r, const std::string& stem) {
  ASSERT_EQ(r.code, 0) << r.output;
  for (const glm::vec3& p : readImage(stem + ".exr").pixels)
    ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
  std::ifstream in(stem + ".json");
  nlohmann::json stats;
  EXPECT_NO_THROW(stats = nlohmann::json::parse(in)) << stem << ".json";
}
}  // namespace

TEST(BadInputCli, SizesOfEveryShapeAreParsedOrRefused) {
  // parseSize once read strtol's end pointer after its string was destroyed (ASan: use after scope / free).
  int w = 0, h = 0;
  parseSize("640x480", w, h);
  EXPECT_EQ(w, 640);
  EXPECT_EQ(h, 480);
  for (const char* s : {"", "x", "8x", "x8", "0x8", "8x0", "-8x8", "8x-8", "8x8x8", "8 x8", "8x8 ",
                        "+8x8junk", "99999999999999999999999999999999x8",
                        "8x99999999999999999999999999999999", "16385x8", "1e3x8", "0x10x"})
    test::expectError([&] { parseSize(s, w, h); }, {"--size", std::string("'") + s + "'"});
  expectRefused(vgi("render --size 123456789012345678901234567890x2 -o " + tmp("s.exr")), {"--size"});
}

TEST(BadInputCli, DeeplyNestedJsonIsRefusedWithoutOverflowingTheStack) {
  expectRefused(renderBad("deep_array.json"), {"deep_array.json", "nested deeper than 64"});
  expectRefused(renderBad("deep_material.json"), {"deep_material.json", "nested deeper than 64"});
  // A huge value quoted in a message is cut short.
  std::string big = tmp("big_array.json");
  {
    std::ofstream f(big);
    f << R"({"meshes": [{"path": "builtin:cornell"}], "camera": {"target": [0, 0, 0], "position": [)";
    for (int i = 0; i < 1000000; ++i) f << (i ? "," : "") << "1";
    f << "]}}";
  }
  CliRun r = vgi("render --scene " + big + " --size 8x8 -o " + tmp("big.exr"));
  expectRefused(r, {"camera.position", "expected an array of 3 numbers", "…"});
  EXPECT_LT(r.output.size(), 1000u);
}

TEST(BadInputCli, NumbersBeyondFloatOrSceneRangeAreRefusedWithTheKey) {
  expectRefused(renderBad("huge_camera.json"), {"huge_camera.json", "camera.position[0]", "1e+308"});
  expectRefused(renderBad("float_overflow_light.json"), {"lights[0].intensity", "1e+39"});
  expectRefused(renderBad("far_camera.json"), {"camera.position", "1e+20"});
  expectRefused(renderBad("huge_scale.json"), {"huge_scale.json", "bounding-box"});
  expectRefused(renderBad("bright_light.json"), {"lights[0] intensity", "exceeds"});
  expectRefused(renderBad("huge_vertex.obj"), {"huge_vertex.obj", "vertex 1", "non-finite"});
  // The reference (Embree asserts on rays that start that far out) says the same.
  expectRefused(renderBad("huge_camera.json", "--method reference"), {"camera.position[0]"});
  expectRefused(vgi("render --set radius=1e39 --size 8x8 -o " + tmp("r.exr")), {"radius", "1e+39"});
  // --camera and --light get the scene file's range checks (a camera 1e20 out aborted inside Embree).
  for (const char* camera : {"1e20,0.27,-0.8,0.278,0.273,0,0,1,0", "0,-2e12,0,0.278,0.273,0,0,0,1",
                             "0.278,0.273,-0.8,3e12,0.273,0,0,1,0"})
    for (const char* method : {"reference --set integrator=direct", "direct"})
      expectRefused(vgi(std::string("render --method ") + method + " --camera " + camera +
                        " --size 8x8 --spp 1 --quiet -o " + tmp("c.exr")),
                    {"--camera", "lies beyond"});
  for (const char* light : {"0=1e15,0,0", "0=0,-3e13,0.2"})
    expectRefused(vgi(std::string("render --method direct --light ") + light +
                      " --size 8x8 --spp 1 --quiet -o " + tmp("l.exr")),
                  {"--light", "lies beyond"});
  // Frame times finite as doubles but not as floats (a frame once wrote "time": null).
  expectRefused(
      vgi("render --frames 2 --time 3e38 --time-step 3e38 --size 8x8 --spp 1 --quiet -o " + tmp("t.exr")),
      {"--time-step", "beyond a 32-bit float"});
  expectRefused(
      vgi("render --frames 3 --time -2e38 --time-step -1e38 --size 8x8 --spp 1 --quiet -o " + tmp("t.exr")),
      {"--frames 3", "beyond a 32-bit float"});
  // A float parameter finite as a double but not as a float is refused by name.
  expectRefused(vgi("render --method vct --set step=1e300 --size 8x8 -o " + tmp("v.exr")),
                {"step", "not a finite 32-bit float"});
}

TEST(BadInputCli, NamesAndPathsThatAreNotUtf8KeepTheStatsValid) {
  // Material and group names with bytes that are not UTF-8, in a file whose name is not UTF-8 either.
  const std::string dir = tmp("utf8_\xff\xfe");
  std::filesystem::create_directories(dir);
  for (const char* f : {"bad_utf8.obj", "bad_utf8.mtl"})
    std::filesystem::copy_file(dataPath(std::string("bad/") + f), dir + "/" + f,
                               std::filesystem::copy_options::overwrite_existing);
  const std::string stem = dir + "/out\xe9";
  expectRendered(
      vgi("render --scene '" + dir + "/bad_utf8.obj' --size 16x16 --spp 1 --quiet -o '" + stem + ".exr'"),
      stem);
  CliRun info = vgi("info --json --scene '" + dir + "/bad_utf8.obj'");
  ASSERT_EQ(info.code, 0) << info.output;
  nlohmann::json parsed;
  EXPECT_NO_THROW(parsed = nlohmann::json::parse(info.output));
}

TEST(BadInputCli, DevicesAndLinksToThemAreNotReadAsFiles) {
  // (These used to hang for ever in OpenImageIO's format probe.)
  expectRefused(renderBad("device_mesh.json"), {"/dev/zero", "not a regular file"});
  const std::string devLink = tmp("zero_link.exr");
  std::filesystem::remove(devLink);
  std::filesystem::create_symlink("/dev/zero", devLink);
  expectRefused(vgi("diff " + devLink + " " + devLink), {devLink, "not a regular file"});
  expectRefused(vgi("diff /dev/urandom /dev/zero"), {"image '/dev/urandom'", "not a regular file"});
  expectRefused(vgi("render --scene /dev/zero -o " + tmp("d.exr")),
                {"scene '/dev/zero'", "not a regular file"});
  // A texture or environment map that is a device: a warning, and the constant colour.
  for (const char* f : {"device_texture.json", "device_env.json"}) {
    CliRun r = renderBad(f);
    expectRendered(r, tmp(std::string("bad_") + f));
    nlohmann::json s = nlohmann::json::parse(std::ifstream(tmp(std::string("bad_") + f + ".json")));
    EXPECT_NE(s["warnings"].dump().find("not a regular file"), std::string::npos) << s["warnings"];
  }
  expectRefused(vgi("diff missing.exr missing2.exr"), {"image 'missing.exr' does not exist"});
}

TEST(BadInputCli, OverlongNameComponentsAreErrorsAboutThePath) {
  const std::string longName(300, 'n');
  expectRefused(vgi("render --size 8x8 -o " + tmp(longName + ".exr")), {"-o", "304 bytes long", "255"});
  expectRefused(vgi("render --scene " + tmp(longName + ".obj") + " -o " + tmp("l.exr")),
                {"scene", "too long"});
  expectRefused(vgi("diff " + tmp(longName + ".exr") + " " + tmp("l.exr")), {"image", "too long"});
}

TEST(BadInputCli, OutputPathsAreCheckedAndMadeBeforeTheRender) {
  // A folder that does not exist yet is made (the README's `-o anim/bunny.exr`).
  const std::string nested = tmp("new_folder/deeper/x.exr");
  std::filesystem::remove_all(tmp("new_folder"));
  expectRendered(vgi("render --method reference --set integrator=ao --size 8x8 --spp 1 --quiet -o " + nested),
                 tmp("new_folder/deeper/x"));
  // --stats naming a folder is refused at once, before the (long) render.
  std::filesystem::create_directories(tmp("stats_dir"));
  std::filesystem::remove(tmp("sd.exr"));
  expectRefused(vgi("render --method reference --spp 100000 --size 256x256 --stats " + tmp("stats_dir") +
                    " -o " + tmp("sd.exr")),
                {"--stats", "is a directory"});
  EXPECT_FALSE(std::filesystem::exists(tmp("sd.exr")));
}

// Experiment files: a field of the wrong JSON type, a grid whose point count would wrap, an output
// no method writes — each refused before anything renders, naming the file, the JSON path and the
// value (never "internal error: type must be string").
TEST(BadInputCli, ExperimentFieldsOfTheWrongTypeOrSizeAreRefusedByPath) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"name_number.json", {"'name'", "42", "string"}},
      {"label_number.json", {"methods[0].label", "7"}},
      {"reference_file_number.json", {"reference.file", "5"}},
      {"reference_method_number.json", {"reference.method", "3"}},
      {"method_reference_method_array.json", {"methods[0].reference.method", "[\"reference\"]"}},
      {"counterpart_of_bool.json", {"methods[0].reference.counterpart_of", "true"}},
      {"device_number.json", {"reference.device", "1"}},
      {"grid_wraps.json", {"methods[0].grid", "10000"}},
      {"grid_too_big.json", {"methods[0].grid", "10000"}},
      {"aov_misspelled.json", {"'aovs'", "indirekt", "direct, indirect"}},
      {"aov_not_written.json", {"'aovs'", "indirect", "none"}},
  };
  const std::string dir = tmp("bad_experiment_out");
  for (auto& [file, needles] : cases) {
    std::filesystem::remove_all(dir);
    const std::string path = dataPath("bad/experiments/" + file);
    CliRun r = vgi("sweep '" + path + "' -o " + dir);
    std::vector<std::string> all = needles;
    all.push_back(path);  // the file is named
    for (auto& n : all)
      EXPECT_NE(r.output.find(n), std::string::npos) << file << ": '" << n << "' in " << r.output;
    EXPECT_EQ(r.code, 2) << file << ": " << r.output;
    EXPECT_EQ(r.output.find("internal"), std::string::npos) << file << ": " << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir + "/references")) << file << ": something rendered";
  }
}

// Nothing is reported written that was not: a results file that is a directory is an error naming
// it, and --stats may not be one of the render's own files (the JSON would replace the image).
TEST(BadInputCli, OutputsThatCannotBeWrittenOrCollideAreRefused) {
  const std::string dir = tmp("sweep_results_dir"), file = tmp("sweep_results_dir.json");
  std::filesystem::remove_all(dir);
  std::ofstream(file) << R"({"scenes": ["builtin:cornell"], "size": "8x8", "spp": 1,
    "reference": {"spp": 1}, "methods": [{"method": "voxel_ao", "set": {"voxels": "16x16x128"}}]})";
  for (const char* blocked : {"results.csv", "results.json"}) {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir + "/" + blocked);
    CliRun r = vgi("sweep " + file + " -o " + dir);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find(blocked), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("is a directory"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("Traceback"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("wrote " + dir + "/" + blocked), std::string::npos) << r.output;
  }
  const std::string stem = tmp("collide");
  for (const std::string& extra :
       {std::string("--stats ") + stem + ".exr", std::string("--stats ") + stem + ".png",
        std::string("--stats ") + stem + ".json", "--aov indirect --stats " + stem + ".indirect.exr",
        "--spp 4 --checkpoints 2 --stats " + stem + ".spp00002.png",
        "--frames 2 --stats " + stem + "_0001.exr"}) {
    CliRun r = vgi("render --method nearfield --set voxels=16x16x128 --size 8x8 --quiet " + extra + " -o " +
                   stem + ".exr");
    EXPECT_EQ(r.code, 2) << extra << ": " << r.output;
    EXPECT_NE(r.output.find("--stats"), std::string::npos) << extra << ": " << r.output;
    EXPECT_NE(r.output.find("also a file this render writes"), std::string::npos) << r.output;
  }
  // Another name is fine.
  expectRendered(vgi("render --method nearfield --set voxels=16x16x128 --size 8x8 --spp 1 --quiet --stats " +
                     stem + ".stats.json -o " + stem + ".exr"),
                 stem);
  EXPECT_TRUE(std::filesystem::exists(stem + ".stats.json"));
}

// Images read to be measured: a NaN or Inf value is refused naming the file and the count (not read
// as 0 into ordinary-looking metrics); a header that claims a thousand channels reads only three.
TEST(BadInputCli, ImagesWithNonFiniteValuesOrManyChannelsAreHandled) {
  Image ok(8, 8);
  for (auto& p : ok.pixels) p = glm::vec3(0.5f);
  writeImage(ok, tmp("finite.exr"));
  for (float bad : {std::nanf(""), INFINITY, -INFINITY}) {
    Image img = ok;
    img.pixels[9].y = bad;
    img.pixels[20] = glm::vec3(bad);
    writeImage(img, tmp("nonfinite.exr"));
    CliRun diff = vgi("diff " + tmp("nonfinite.exr") + " " + tmp("finite.exr"));
    expectRefused(diff, {tmp("nonfinite.exr"), "4 non-finite"});
    CliRun cmp =
        vgi("compare --method voxel_ao --set voxels=16x16x128 --size 8x8 --spp 1 --quiet --reference " +
            tmp("nonfinite.exr") + " -o " + tmp("cmp_nf.exr"));
    expectRefused(cmp, {tmp("nonfinite.exr"), "non-finite"});
  }
  // 1000 channels (the first three are the image).
  {
    using namespace OIIO;
    const int w = 8, h = 8, nc = 1000;
    ImageSpec spec(w, h, nc, TypeDesc::HALF);
    std::vector<float> px(size_t(w) * h * nc, 0.25f);
    auto out = ImageOutput::create(tmp("many_channels.exr"));
    ASSERT_TRUE(out && out->open(tmp("many_channels.exr"), spec));
    ASSERT_TRUE(out->write_image(TypeDesc::FLOAT, px.data()));
    out->close();
  }
  CliRun many = vgi("diff " + tmp("many_channels.exr") + " " + tmp("finite.exr"));
  EXPECT_EQ(many.code, 0) << many.output;
  EXPECT_EQ(many.output.find("internal"), std::string::npos) << many.output;
  EXPECT_NE(many.output.find("0.25"), std::string::npos) << "the first three channels read: " << many.output;
}

// Ctrl-C during a sweep: exit 130 (the README's scheme), naming where it stopped; the run resumes.
TEST(BadInputCli, AnInterruptedSweepExits130) {
  const std::string file = tmp("sweep_sigint.json"), dir = tmp("sweep_sigint");
  std::filesystem::remove_all(dir);
  std::ofstream(file) << R"({"scenes": ["builtin:cornell"], "size": "64x64", "spp": 100000,
    "reference": {"spp": 100000}, "methods": [{"method": "direct"}]})";
  // timeout signals its process group: the sweep and the render it waits for, as a terminal's Ctrl-C.
  CliRun r = test::shell("timeout --preserve-status -s INT 4 " + std::string(VGI_BINARY) + " sweep " + file +
                         " -o " + dir);
  EXPECT_EQ(r.code, 130) << r.output;
  EXPECT_NE(r.output.find("interrupted during"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("run it again to resume"), std::string::npos) << r.output;
}

// Large GL allocations are estimated and refused before they are made, naming the parameter, its
// value and the bytes against the budget (core/gpu_memory.h) — not left to fail in the driver.
TEST(BadInputCli, AllocationsBeyondTheDeviceAreRefusedByParameter) {
  expectRefused(renderBad("ten_point_lights.json", "--method nearfield --set shadow_res=8192"),
                {"shadow_res", "8192", "10 light(s)", "MiB"});
  expectRefused(renderBad("ten_point_lights.json", "--method direct --set shadow_res=8192"),
                {"shadow_res", "8192", "MiB"});
  expectRendered(renderBad("ten_point_lights.json", "--method nearfield --set shadow_res=64"),
                 tmp("bad_ten_point_lights.json"));
  for (const char* grid : {"512", "256", "1024"})
    expectRefused(vgi(std::string("render --method avg --set grid=") + grid + " --size 8x8 --quiet -o " +
                      tmp("avg_big.exr")),
                  {"grid", grid, std::string(grid) == "1024" ? "GiB" : "MiB"});
}

TEST(BadInputCli, UsageErrorsExitTwoAndNameTheClosestOption) {
  CliRun r = vgi("render --methdo nearfield");
  expectRefused(r, {"--methdo", "did you mean '--method'"});
  expectRefused(vgi("rendr"), {"did you mean 'vgi render'"});
  expectRefused(vgi("render --help-module nearfeld"), {"--help-module", "nearfeld", "nearfield"});
  expectRefused(vgi("render --spp notanumber"), {"--spp"});
  expectRefused(vgi("render --accumulate kahan"), {"--accumulate", "kahan", "compensated or plain"});
  expectRefused(vgi("render --spp 4 --checkpoints 1,x"), {"--checkpoints", "'x'"});
  expectRefused(vgi("render --spp 4 --checkpoints 1,8"), {"--checkpoints", "8", "--spp 4"});
  expectRefused(vgi("render --spp 4 --checkpoints 0"), {"--checkpoints", "0"});
  expectRefused(vgi("render --spp 4 --frames 2 --checkpoints 2"), {"--checkpoints", "--frames 2"});
  expectRefused(vgi("voxelize --kind binary,normal --textures cubic"), {"--textures", "'cubic'"});
  expectRefused(vgi("voxelize --textures isotropic"), {"--textures", "multi-valued"});
  EXPECT_EQ(vgi("render --help").code, 0);
}

TEST(BadInputCli, AStillInterruptedBeforeItsFirstSampleWritesNothing) {
  const std::string out = tmp("first.exr");
  std::filesystem::remove(out);
  std::filesystem::remove(tmp("first.json"));
  // A background job of a non-interactive shell ignores SIGINT until vgi installs its handler: the
  // signal must come after start-up (2 s, with a render long enough to still be running on a loaded machine).
  CliRun r = vgi("render --method reference --set integrator=path --size 3072x3072 --spp 1 --quiet -o " +
                 out + " 2>&1 & pid=$!; sleep 2; kill -INT $pid; wait $pid");
  ASSERT_EQ(r.code, 130) << r.output;
  EXPECT_NE(r.output.find("nothing written"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_FALSE(std::filesystem::exists(tmp("first.json")));
}

TEST(BadInputCli, HelpModuleUsesTheScenesDefaults) {
  // The radius default is 0.1 × the scene's diagonal: the open scene's, not the Cornell box's.
  CliRun cornell = vgi("render --help-module nearfield");
  CliRun open = vgi("render --help-module nearfield --scene " + dataPath("open_scene.obj"));
  ASSERT_EQ(open.code, 0) << open.output;
  EXPECT_NE(cornell.output, open.output);
  EXPECT_NE(open.output.find("open_scene.obj"), std::string::npos) << open.output;
}

TEST(BadInputCli, APresetForOneMethodSelectsItOrSaysSo) {
  const std::string scene = dataPath("bad/preset_for_reference.json");
  CliRun ok = vgi("render --scene " + scene + " --preset ao --size 8x8 --spp 1 --quiet -o " + tmp("pa.exr"));
  ASSERT_EQ(ok.code, 0) << ok.output;
  nlohmann::json s = nlohmann::json::parse(std::ifstream(tmp("pa.json")));
  EXPECT_EQ(s["method"], "reference");
  EXPECT_EQ(s["params"]["integrator"], "ao");
  expectRefused(vgi("render --scene " + scene + " --preset ao --method nearfield -o " + tmp("pb.exr")),
                {"--preset 'ao'", "method 'reference'"});
}

TEST(BadInputCli, StatsAreConsistentAndInfoShowsWhatALightHas) {
  CliRun r = vgi("render --size 16x16 --spp 1 --quiet -o " + tmp("sp.exr"));
  ASSERT_EQ(r.code, 0) << r.output;
  nlohmann::json s = nlohmann::json::parse(std::ifstream(tmp("sp.json")));
  EXPECT_EQ(s["method"], "nearfield");  // the default
  for (auto& p : s["sample_passes"]) EXPECT_TRUE(s["timings_ms"].contains(p.get<std::string>())) << p;
  // A scene without lights gets a point light: no direction, no cone.
  CliRun i = vgi("info --json --scene " + dataPath("open_scene.obj"));
  ASSERT_EQ(i.code, 0) << i.output;
  nlohmann::json l = nlohmann::json::parse(i.output)["lights"][0];
  EXPECT_EQ(l["type"], "point");
  EXPECT_FALSE(l.contains("direction"));
  EXPECT_FALSE(l.contains("cone_deg"));
  CliRun spot = vgi("info --json");
  nlohmann::json ls = nlohmann::json::parse(spot.output)["lights"][0];
  EXPECT_EQ(ls["type"], "spot");
  EXPECT_TRUE(ls.contains("cone_deg"));
}

TEST(BadInputCli, NonManifoldFansVoxelizeWithTheAtlas) {
  // segmentCharts splits each refused face off with its own vertices; the
  // copies came from a reference into the array being grown (ASan: use after free).
  CliRun r = vgi("voxelize --scene " + dataPath("bad/nonmanifold_fan.obj") +
                 " --voxels 64x64x128 --voxelizer atlas --no-cache --stats " + tmp("fan.json"));
  ASSERT_EQ(r.code, 0) << r.output;
  nlohmann::json s = nlohmann::json::parse(std::ifstream(tmp("fan.json")));
  EXPECT_GT(s["voxels_set"].get<long>(), 0);
}

TEST(BadInputCli, CoincidentGeometryLoadsInLinearTime) {
  // Class 10 of issue 33: assimp's GenSmoothNormals walked every corner at a position for each corner
  // there (10^4 copies of one triangle took 2 s, 10^6 never loaded); core/smooth_normals.h groups them.
  // At 3e5 the old loader would run for about half an hour: this test's timeout catches a regression.
  auto write = [](const std::string& name, const std::function<void(std::ostream&)>& body) {
    std::ofstream f(tmp(name));
    body(f);
    return tmp(name);
  };
  const std::string copies = write("copies.obj", [](std::ostream& f) {
    f << "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (int i = 0; i < 300000; ++i) f << "f 1 2 3\n";
  });
  // A disc of 1e5 coplanar triangles around one vertex, and a cone of 2000 facets: its apex holds more
  // distinct normals than the bound and stays flat, with a warning naming the file.
  auto fan = [](std::ostream& f, int n, float apex) {
    f << "v 0 0 " << apex << "\n";
    for (int i = 0; i <= n; ++i)
      f << "v " << std::cos(2 * M_PI * i / n) << ' ' << std::sin(2 * M_PI * i / n) << " 0\n";
    for (int i = 0; i < n; ++i) f << "f 1 " << i + 2 << ' ' << i + 3 << '\n';
  };
  const std::string disc = write("disc.obj", [&](std::ostream& f) { fan(f, 100000, 0.0f); });
  const std::string cone = write("cone.obj", [&](std::ostream& f) { fan(f, 2000, 1.0f); });
  CliRun c = vgi("info --scene " + copies);
  ASSERT_EQ(c.code, 0) << c.output;
  EXPECT_NE(c.output.find("triangles  300000 "), std::string::npos) << c.output;
  CliRun d = vgi("info --scene " + disc);
  ASSERT_EQ(d.code, 0) << d.output;
  EXPECT_NE(d.output.find("triangles  100000 "), std::string::npos) << d.output;
  CliRun k = vgi("info --scene " + cone);
  ASSERT_EQ(k.code, 0) << k.output;
  EXPECT_NE(k.output.find("cone.obj: mesh 'defaultobject': 1 vertex position(s) shared by more than 1024"),
            std::string::npos)
      << k.output;
  // And they render: the exact counterpart over the copies, the direct method over the cone.
  expectRendered(vgi("render --scene " + copies + " --method reference --size 16x16 --spp 1 --quiet -o " +
                     tmp("copies.exr")),
                 tmp("copies"));
  expectRendered(
      vgi("render --scene " + cone + " --method direct --size 16x16 --spp 1 --quiet -o " + tmp("cone.exr")),
      tmp("cone"));
}

TEST(BadInputCli, VoxelGridsFarFromTheOriginAreComplete) {
  // Class 11 of issue 33: the atlas kept world positions, which far from the origin snap to a float's
  // step (1 unit at 1e7): a unit box there set 8 voxels, recall 0.00008, with exit 0. Georeferenced-style
  // coordinates, in the mesh's own vertices and through a scene file's transform; every voxelizer that
  // finds all of a closed box at the origin finds all of it here (`vgi voxelize` compares with exact).
  {
    std::ofstream f(tmp("far_box.obj"));
    for (int i = 0; i < 8; ++i)
      f << "v " << 10000000 + (i & 1) << ' ' << 10000000 + (i >> 1 & 1) << ' ' << 10000000 + (i >> 2) << '\n';
    f << "f 1 2 4 3\nf 5 7 8 6\nf 1 5 6 2\nf 3 4 8 7\nf 1 3 7 5\nf 2 6 8 4\n";
    std::ofstream(tmp("near_cube.obj"))
        << "v 0 0 0\nv 10 0 0\nv 0 10 0\nv 10 10 0\nv 0 0 10\nv 10 0 10\nv 0 10 10\n"
           "v 10 10 10\nf 1 2 4 3\nf 5 7 8 6\nf 1 5 6 2\nf 3 4 8 7\nf 1 3 7 5\nf 2 6 8 4\n";
    std::ofstream(tmp("far_cube.json"))
        << R"({"meshes": [{"path": "near_cube.obj", "transform": {"translate": [5e5, 5e6, 0]}}]})";
  }
  for (const std::string& scene : {tmp("far_box.obj"), tmp("far_cube.json")})
    for (const char* voxelizer : {"atlas", "conservative", "hybrid"}) {
      const std::string stats = tmp(std::string("far_") + voxelizer + ".json");
      CliRun r = vgi("voxelize --scene " + scene + " --voxels 128 --no-cache --voxelizer " + voxelizer +
                     " --stats " + stats);
      ASSERT_EQ(r.code, 0) << r.output;
      nlohmann::json s = nlohmann::json::parse(std::ifstream(stats));
      EXPECT_GE(s["recall"].get<double>(), 0.999) << scene << " " << voxelizer;
      EXPECT_GE(s["precision"].get<double>(), 0.999) << scene << " " << voxelizer;
    }
}

}  // namespace vgi
