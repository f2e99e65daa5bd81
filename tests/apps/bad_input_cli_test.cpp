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
#include "core/image_metrics.h"
#include "core/json_text.h"
#include "experiments/sweep.h"
#include "illum/run/render_job.h"
#include "illum/run/render_outputs.h"

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
  // A texture or environment map the scene file names that is a device: refused, naming the key.
  expectRefused(renderBad("device_texture.json"), {"materials.m.texture", "/dev/zero", "not a regular file"});
  expectRefused(renderBad("device_env.json"), {"environment.map", "/dev/urandom", "not a regular file"});
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
      // Animation values finite as doubles but not as the renders' floats: refused at load, by key.
      {"time_step_overflow.json", {"scene 'builtin:cornell'", "'time_step'", "1e+300", "32-bit float"}},
      {"last_frame_overflow.json",
       {"'time' 3e+38", "'time_step' 3e+38", "last frame's time", "32-bit float"}},
      // "device": "same" is done or refused: the curve of a counterpart reference_gl cannot run.
      {"device_same_refused.json", {"'reference.device' = \"same\"", "methods[0]", "visibility", "\"cpu\""}},
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

// Issue 45, class 4: reference.device is what the curves do, and results.json says what they did. "cpu"
// with a reference naming reference_gl runs its CPU twin (it ran on GL while the file said "cpu").
TEST(BadInputCli, TheReferenceDeviceIsDoneAndRecorded) {
  const std::string file = tmp("device_cpu.json"), dir = tmp("device_cpu_out");
  std::filesystem::remove_all(dir);
  std::ofstream(file) << R"({"scenes": ["builtin:cornell"], "size": "8x8", "spp": 1,
    "reference": {"device": "cpu", "spp": 1, "convergence": [1], "method": "reference_gl",
                  "set": {"integrator": "ao", "radius": 0.2}},
    "methods": [{"method": "voxel_ao", "set": {"voxels": "16x16x128", "radius": 0.2}}]})";
  const Experiment e = loadExperiment(file, dir);
  ASSERT_EQ(e.curves.size(), 1u);
  EXPECT_EQ(e.curves[0].options.method, "reference");
  EXPECT_EQ(e.curveChoice[0].device, "cpu");
  CliRun r = vgi("sweep " + file + " -o " + dir);
  ASSERT_EQ(r.code, 0) << r.output;
  const nlohmann::json res = nlohmann::json::parse(std::ifstream(dir + "/results.json"));
  EXPECT_EQ(res["exact_device"], "cpu");
  EXPECT_EQ(res["exact_device_given"], true);
  int curves = 0;
  for (auto& row : res["rows"])
    if (row["role"] == "counterpart") {
      ++curves;
      EXPECT_EQ(row["method"], "reference");
      EXPECT_EQ(row["device"], "cpu");
      EXPECT_EQ(row["same_device"], false);
    }
  EXPECT_EQ(curves, 1);
}

// Issue 45, class 1 and 2: every ray handed to Embree is valid and no image is silently empty. A near
// plane beyond the scene (1e20 put the reference's ray origins beyond Embree's range: SIGABRT) is
// refused by key; a denormal one renders what no near plane renders (it was black for the raster
// methods); a camera path whose up passes through the zero vector renders its keys' camera there.
TEST(BadInputCli, CutAwaysAndCameraPathsGiveValidRaysAndNoEmptyImage) {
  for (const char* method : {"reference --set integrator=direct", "direct", "vct_ao"})
    expectRefused(renderBad("near_beyond_scene.json", std::string("--method ") + method),
                  {"near_beyond_scene.json", "camera.near", "1e+20", "beyond the whole scene"});
  expectRefused(
      vgi("compare --method direct --exact-device cpu --scene '" + dataPath("bad/near_beyond_scene.json") +
          "' --size 8x8 --spp 1 --ref-spp 1 --quiet -o " + tmp("nb.exr")),
      {"camera.near", "beyond the whole scene"});
  expectRefused(renderBad("near_beyond_path_key.json", "--method direct"),
                {"camera.near at camera.keyframes[1]", "1.2", "0.759"});
  // --camera moves the eye: the scene's cut-away is checked against the new pose too.
  const std::string pose = R"("position": [0.278, 0.273, -0.8], "target": [0.278, 0.273, 0])";
  std::ofstream(tmp("near_1_2.json"))
      << R"({"meshes": [{"path": "builtin:cornell"}], "camera": {)" << pose << R"(, "near": 1.2}})";
  std::ofstream(tmp("no_near.json")) << R"({"meshes": [{"path": "builtin:cornell"}], "camera": {)" << pose
                                     << "}}";
  expectRefused(vgi("render --scene " + tmp("near_1_2.json") +
                    " --camera 0.278,0.273,-0.2,0.278,0.273,0,0,1,0 --method direct --size 8x8 --quiet -o " +
                    tmp("nc.exr")),
                {"--camera", "camera.near", "beyond the whole scene"});
  auto meanOf = [](const std::string& exr) {
    double sum = 0;
    const Image img = readImage(exr);
    for (auto& p : img.pixels) sum += double(p.x) + p.y + p.z;
    return sum / double(img.pixels.size());
  };
  for (const char* method : {"direct", "vct_ao", "reference"}) {
    const std::string stem = tmp(std::string("denormal_") + method), plain = stem + "_plain";
    expectRendered(vgi("render --scene '" + dataPath("bad/near_denormal.json") + "' --method " + method +
                       " --size 16x16 --spp 1 --quiet -o " + stem + ".exr"),
                   stem);
    ASSERT_EQ(vgi("render --scene " + tmp("no_near.json") + " --method " + method +
                  " --size 16x16 --spp 1 --quiet -o " + plain + ".exr")
                  .code,
              0);
    EXPECT_GT(meanOf(stem + ".exr"), 0.01) << method << ": black";
    // A near plane of 1e-39 cuts nothing away: the image of the same camera without one.
    EXPECT_EQ(compareImages(readImage(stem + ".exr"), readImage(plain + ".exr")).relMae, 0.0) << method;
  }
  const std::string flip = dataPath("bad/up_flip_path.json");
  for (const char* method : {"reference --set integrator=direct", "direct"}) {
    const std::string stem = tmp("flip_mid");
    expectRendered(vgi("render --scene '" + flip + "' --method " + method +
                       " --time 0.5 --size 16x16 --spp 1 --quiet -o " + stem + ".exr"),
                   stem);
    EXPECT_GT(meanOf(stem + ".exr"), 0.01) << method;
  }
  const std::string frames = tmp("flip_frames");
  ASSERT_EQ(
      vgi("render --scene '" + flip + "' --method direct --frames 3 --time-step 0.5 --size 16x16 --spp 1 " +
          "--quiet -o " + frames + ".exr")
          .code,
      0);
  for (int f = 0; f < 3; ++f) EXPECT_GT(meanOf(frameStem(frames, f) + ".exr"), 0.01) << "frame " << f;
  CliRun cmp = vgi("compare --method direct --scene '" + flip +
                   "' --time 0.5 --size 16x16 --spp 1 --ref-spp 1 --quiet -o " + tmp("flip_cmp.exr"));
  EXPECT_EQ(cmp.code, 0) << cmp.output;
}

// Issue 45, class 5: a metric with no value is "undefined" (core/json_text.h), never null, in every
// output; the sweep's report survives a black reference (it crashed, and vgi blamed matplotlib).
TEST(BadInputCli, MetricsWithoutAValueSaySoAndTheReportSurvivesThem) {
  Image lit(8, 8), black(8, 8);
  for (auto& p : lit.pixels) p = glm::vec3(0.5f, 0.25f, 0.125f);
  for (auto& p : black.pixels) p = glm::vec3(0.0f);
  writeImage(lit, tmp("lit.exr"));
  writeImage(black, tmp("black.exr"));
  auto noNull = [](const CliRun& r) {
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(r.output.find("null"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("nan"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("inf"), std::string::npos) << r.output;
  };
  CliRun j = vgi("diff " + tmp("lit.exr") + " " + tmp("black.exr") + " --json");
  noNull(j);
  const nlohmann::json d = nlohmann::json::parse(j.output);
  EXPECT_EQ(d["leak"], "undefined");
  EXPECT_EQ(d["rel_mae"], "undefined");
  EXPECT_EQ(d["energy_rgb"][0], "undefined");
  EXPECT_GT(d["rmse"].get<double>(), 0.0);  // what has a value keeps it
  noNull(vgi("diff " + tmp("lit.exr") + " " + tmp("black.exr")));
  noNull(vgi("diff " + tmp("lit.exr") + " " + tmp("lit.exr") + " --dark-tolerance 1e308 --json"));
  noNull(vgi("diff " + tmp("lit.exr") + " " + tmp("black.exr") + " --relative-epsilon 0.1 --json"));
  for (int f = 0; f < 2; ++f) {
    Image changing = lit;
    for (auto& p : changing.pixels) p *= float(1 + f);  // it changes; the dark reference does not
    writeImage(changing, frameStem(tmp("seq_lit"), f) + ".exr");
    writeImage(black, frameStem(tmp("seq_dark"), f) + ".exr");
  }
  CliRun seq = vgi("diff --frames 2 " + tmp("seq_lit.exr") + " " + tmp("seq_dark.exr") + " --json");
  noNull(seq);
  EXPECT_EQ(nlohmann::json::parse(seq.output)["temporal_error"], "undefined");
  // A sweep against an all-black reference file: results, CSV and report, every metric a number or "undefined".
  const std::string file = tmp("black_ref.json"), dir = tmp("black_ref_out");
  std::filesystem::remove_all(dir);
  std::ofstream(file) << R"({"scenes": ["builtin:cornell"], "size": "8x8", "spp": 2, "checkpoints": [1],
    "reference": {"file": ")"
                      << tmp("black.exr") << R"("}, "methods": [{"method": "direct"}]})";
  CliRun sweep = vgi("sweep " + file + " -o " + dir);
  ASSERT_EQ(sweep.code, 0) << sweep.output;
  EXPECT_EQ(sweep.output.find("Traceback"), std::string::npos) << sweep.output;
  EXPECT_TRUE(std::filesystem::exists(dir + "/report.html"));
  std::ifstream res(dir + "/results.json");
  const std::string text((std::istreambuf_iterator<char>(res)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.find("null"), std::string::npos);
  EXPECT_EQ(nlohmann::json::parse(text)["rows"][0]["image"]["rel_mae"], "undefined");
}

// Issue 45, class 6: --print-job prints only a job `vgi render --job` renders.
TEST(BadInputCli, PrintJobValidatesWhatItPrints) {
  expectRefused(vgi("render --method vtc --print-job"), {"--method", "vtc"});
  expectRefused(vgi("render --method vct --set volumee=svo --print-job"), {"volumee=svo", "volume"});
  expectRefused(vgi("render --method vct --aov bogus --print-job"), {"--aov 'bogus'"});
  expectRefused(vgi("render --scene /nonexistent/s.obj --print-job"), {"/nonexistent/s.obj"});
  expectRefused(vgi("render --light 7=0,0,0 --print-job"), {"--light", "7"});
  CliRun ok = vgi("render --method vct --set volume=svo --size 8x8 --spp 1 --print-job");
  ASSERT_EQ(ok.code, 0) << ok.output;
  std::ofstream(tmp("printed_job.json")) << ok.output;
  expectRendered(vgi("render --job " + tmp("printed_job.json") + " -o " + tmp("printed_job_out.exr")),
                 tmp("printed_job_out"));
}

// Issue 45, class 8: the stats beside a --reference image are checked before they are used.
TEST(BadInputCli, CompareChecksTheStatsBesideAReferenceImage) {
  const std::string stem = tmp("ref_stats");
  ASSERT_EQ(
      vgi("render --method reference --set integrator=ao --size 8x8 --spp 1 --quiet -o " + stem + ".exr")
          .code,
      0);
  const nlohmann::json good = nlohmann::json::parse(std::ifstream(stem + ".json"));
  for (const auto& [key, value] : std::vector<std::pair<std::string, nlohmann::json>>{{"spp", "many"},
                                                                                      {"spp", nullptr},
                                                                                      {"spp", 1e300},
                                                                                      {"spp", 0},
                                                                                      {"total_ms", "soon"},
                                                                                      {"wall_ms", -1}}) {
    nlohmann::json bad = good;
    bad[key] = value;
    std::ofstream(stem + ".json") << bad.dump();
    CliRun r =
        vgi("compare --method voxel_ao --set voxels=16x16x128 --size 8x8 --spp 1 --quiet --reference " +
            stem + ".exr -o " + tmp("ref_stats_cmp.exr"));
    expectRefused(r, {stem + ".json", "\"" + key + "\"", jsonExcerpt(value)});
  }
  std::ofstream(stem + ".json") << good.dump();
  CliRun ok = vgi("compare --method voxel_ao --set voxels=16x16x128 --size 8x8 --spp 1 --quiet --reference " +
                  stem + ".exr -o " + tmp("ref_stats_cmp.exr"));
  EXPECT_EQ(ok.code, 0) << ok.output;
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
        "--aov indirect --stats " + stem + ".indirect.exr",
        "--spp 4 --checkpoints 2 --stats " + stem + ".spp00002.png",
        "--frames 2 --stats " + stem + "_0001.exr"}) {
    CliRun r = vgi("render --method nearfield --set voxels=16x16x128 --size 8x8 --quiet " + extra + " -o " +
                   stem + ".exr");
    EXPECT_EQ(r.code, 2) << extra << ": " << r.output;
    EXPECT_NE(r.output.find("--stats"), std::string::npos) << extra << ": " << r.output;
    EXPECT_NE(r.output.find("also a file this render writes"), std::string::npos) << r.output;
  }
  // The render's own stats file is what --stats would write: accepted, written once, with its outputs.
  expectRendered(vgi("render --method nearfield --set voxels=16x16x128 --size 8x8 --spp 1 --quiet --stats " +
                     stem + ".json -o " + stem + ".exr"),
                 stem);
  EXPECT_TRUE(nlohmann::json::parse(std::ifstream(stem + ".json")).contains("outputs"));
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

TEST(BadInputCli, WarningsArePrintedOnceEvenWhenQuiet) {
  // Issue 53, class 1: a scene's warnings reached only the stats JSON. Now each is printed to stderr
  // ("vgi: warning: …") as well as recorded, under --quiet too, and once per process (compare loads
  // its scene twice).
  auto count = [](const std::string& text, const std::string& needle) {
    size_t n = 0;
    for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
    return n;
  };
  const std::string missing = dataPath("bad/missing_texture.obj");  // a model file's texture: a warning
  CliRun r = renderBad("missing_texture.obj");
  expectRendered(r, tmp("bad_missing_texture.obj"));
  EXPECT_EQ(count(r.output, "vgi: warning: texture '"), 1u) << r.output;
  EXPECT_NE(r.output.find("no_such_texture.png"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("vgi: warning: " + missing + ": no lights, added a point light"), std::string::npos)
      << r.output;
  nlohmann::json s = nlohmann::json::parse(std::ifstream(tmp("bad_missing_texture.obj.json")));
  EXPECT_NE(s["warnings"].dump().find("no_such_texture.png"), std::string::npos) << s["warnings"];
  CliRun c = vgi("compare --scene '" + dataPath("bad/too_bright.obj") +
                 "' --method direct --size 16x16 --spp 1 --ref-spp 1 -o " + tmp("warn_compare.exr"));
  ASSERT_EQ(c.code, 0) << c.output;
  EXPECT_EQ(count(c.output, "ks reduced"), 1u) << c.output;
  // An option's warning too: --frames over a scene that does not move.
  CliRun f = vgi("render --method direct --size 8x8 --spp 1 --frames 2 --quiet -o " + tmp("still/f.exr"));
  ASSERT_EQ(f.code, 0) << f.output;
  EXPECT_NE(f.output.find("vgi: warning: --frames 2: the scene has no dynamic meshes"), std::string::npos)
      << f.output;
  // The other commands that load a scene print them too.
  CliRun v =
      vgi("voxelize --scene '" + missing + "' --voxels 32x32x128 --no-cache --stats " + tmp("warn_vox.json"));
  ASSERT_EQ(v.code, 0) << v.output;
  EXPECT_EQ(count(v.output, "vgi: warning: texture '"), 1u) << v.output;
}

TEST(BadInputCli, MapsAndTexturesTheSceneFileNamesMustBeReadable) {
  // Issue 53, class 1: an environment map that was an empty file or a folder rendered with exit 0 and
  // the constant colour. What the scene file itself names is refused (exit 2, the key and the file).
  const std::string empty = tmp("empty_map.hdr"), folder = tmp("map_folder");
  std::ofstream(empty).close();
  std::filesystem::create_directories(folder);
  for (const std::string& map : {empty, folder, tmp("no_such_map.exr")}) {
    const std::string scene = tmp("env_scene.json");
    std::ofstream(scene) << R"({"meshes": [{"path": "builtin:cornell"}], "environment": {"map": ")" << map
                         << R"("}})";
    expectRefused(vgi("render --scene " + scene + " --size 8x8 --spp 1 --quiet -o " + tmp("env.exr")),
                  {"environment.map", map});
    std::ofstream(scene) << R"({"meshes": [{"path": "builtin:cornell", "material": "m"}],)"
                         << R"( "materials": {"m": {"texture": ")" << map << R"("}}})";
    expectRefused(vgi("render --scene " + scene + " --size 8x8 --spp 1 --quiet -o " + tmp("tex.exr")),
                  {"materials.m.texture", map});
  }
}

TEST(BadInputCli, MeasurementScriptsCheckTheirArgumentsAndPassOnVgisReason) {
  // Issue 53, class 2: the scripts a README or BENCHMARKS tells a person to run ended in a Python
  // traceback on a missing vgi or folder, and `channel_energy.py` swallowed vgi's reason. Each now
  // checks its arguments up front (exit 2, naming the argument and the value; scripts/script_args.*)
  // and a failed vgi command is reported with vgi's own "vgi: error: …".
  const std::string scripts = dataPath("../../scripts"), vgiPath = VGI_BINARY;
  const std::string empty = tmp("script_empty_dir"), out = tmp("script_out");
  std::filesystem::create_directories(empty);
  auto refused = [&](const std::string& command, std::initializer_list<std::string> needles) {
    CliRun r = test::shell("cd " + scripts + "/.. && " + command);
    EXPECT_EQ(r.code, 2) << command << "\n" << r.output;
    for (auto& n : needles)
      EXPECT_NE(r.output.find(n), std::string::npos) << "'" << n << "' not in: " << r.output;
    EXPECT_EQ(r.output.find("Traceback"), std::string::npos) << command << "\n" << r.output;
    EXPECT_EQ(r.output.find("unbound variable"), std::string::npos) << command << "\n" << r.output;
  };
  const std::string py = "python3 scripts/";
  refused(py + "driver_parity.py run --vgi /no/such/vgi " + out, {"--vgi", "/no/such/vgi", "does not exist"});
  refused(py + "driver_parity.py render --vgi " + vgiPath + " --size 0x3 " + out, {"--size", "0x3"});
  refused(py + "driver_parity.py render --vgi " + vgiPath + " --spp many " + out, {"--spp", "many"});
  refused(py + "driver_parity.py render --vgi " + vgiPath + " --only nosuch " + out, {"--only", "nosuch"});
  refused(py + "driver_parity.py compare --vgi " + vgiPath + " " + empty + " " + empty,
          {empty, "manifest.json"});
  refused(py + "channel_energy.py --vgi /no/such/vgi " + out, {"--vgi", "/no/such/vgi"});
  refused(py + "channel_energy.py --vgi " + vgiPath + " --scenes /no/scene.json " + out,
          {"--scenes", "/no/scene.json"});
  refused(py + "channel_energy.py --vgi " + vgiPath + " --size big " + out, {"--size", "big"});
  refused(py + "artefacts_tables.py " + empty, {empty, "results.json"});
  refused(py + "artefacts_tables.py", {"usage"});
  refused(py + "artefacts_remedies_tables.py", {"usage"});
  refused(py + "artefacts_remedies_tables.py " + empty, {empty, "results.json"});
  refused(py + "svo_tables.py", {"usage"});
  refused(py + "split_tables.py", {"usage"});
  refused(py + "check_doc_paths.py a b", {"usage"});
  refused(py + "check_doc_paths.py /no/such/dir", {"/no/such/dir", "not a folder"});
  refused(py + "split_tables.py /no/such/dir", {"/no/such/dir", "does not exist"});
  refused(py + "svo_tables.py /no/such/dir", {"/no/such/dir", "does not exist"});
  refused(py + "sweep_report.py " + empty, {empty, "results.json"});
  refused(py + "make_leak_walls.py extra", {"usage", "extra"});
  refused(py + "make_atrium.py extra", {"usage", "extra"});
  {  // results of another experiment
    std::ofstream(empty + "/results.json") << R"({"experiment": "other", "rows": [{"role": "point"}]})";
    refused(py + "svo_tables.py " + empty, {"'other'", "svo.json"});
    refused(py + "split_tables.py " + empty, {"'other'", "equal-time-split.json"});
    refused(py + "artefacts_remedies_tables.py " + empty, {"'other'", "artefacts-remedies.json"});
    std::filesystem::remove(empty + "/results.json");
  }
  refused("bash scripts/bench_traverse.sh a b", {"usage"});
  refused("VGI=/no/such/vgi bash scripts/bench_load.sh", {"VGI", "/no/such/vgi"});
  refused("VGI=" + vgiPath + " bash scripts/bench_load.sh " + out + " 0", {"max-triangles", "'0'"});
  refused("VGI=" + vgiPath + " bash scripts/bench_radius.sh " + out + " -3", {"ref-spp", "'-3'"});
  refused("VGI=" + vgiPath + " bash scripts/bench_vct.sh " + out + " 9", {"SECTIONS", "'9'"});
  refused("VGI=" + vgiPath + " bash scripts/bench_hybrid.sh extra", {"usage"});
  refused("VGI=" + vgiPath + " bash scripts/bench_vct.sh /dev/null",
          {"OUT_DIR", "/dev/null", "not a folder"});
  refused("bash scripts/bench_atlas.sh a b", {"usage"});
  refused("bash scripts/bench_voxelize.sh a b", {"usage"});
  refused("bash scripts/render_fingerprints.sh", {"usage"});
  refused("bash scripts/render_fingerprints.sh " + out + " /no/such/vgi", {"VGI", "/no/such/vgi"});
  refused("VGI=" + vgiPath + " bash scripts/sweep_slurm.sh /no/such.json " + out,
          {"EXPERIMENT", "/no/such.json"});
  refused("bash scripts/sweep_slurm.sh one", {"usage"});
  refused("bash scripts/demo.sh " + out + " 0", {"FRAMES", "'0'"});
  refused("bash scripts/demo.sh " + out + " 2 640x", {"SIZE", "'640x'"});
  refused("bash scripts/demo.sh " + out + " 2 64x36 1 /no/such/vgi", {"VGI", "/no/such/vgi"});
  refused("bash scripts/demo.sh a 1 2x2 1 b c", {"usage"});
  refused("bash scripts/gpu_bench.sh --vgi", {"usage", "--vgi needs a value"});
  refused("bash scripts/gpu_bench.sh --vgi /no/such/vgi " + out, {"--vgi", "/no/such/vgi"});
  // A vgi command that fails: its reason reaches the person, from Python and from the shell.
  CliRun c = test::shell("cd " + scripts + "/.. && " + py + "channel_energy.py --vgi " + vgiPath +
                         " --scenes builtin:cornell --methods nosuchmethod " + out);
  EXPECT_EQ(c.code, 1) << c.output;
  EXPECT_NE(c.output.find("vgi: error:"), std::string::npos) << c.output;
  EXPECT_NE(c.output.find("nosuchmethod"), std::string::npos) << c.output;
  EXPECT_EQ(c.output.find("Traceback"), std::string::npos) << c.output;
  CliRun sh = test::shell("bash -c '. " + scripts + "/script_args.sh; sa_run " + tmp("sa_run.log") + " " +
                          vgiPath + " render --method nosuchmethod -o " + tmp("x.exr") + "'");
  EXPECT_EQ(sh.code, 1) << sh.output;
  EXPECT_NE(sh.output.find("FAILED"), std::string::npos) << sh.output;
  EXPECT_NE(sh.output.find("vgi: error:"), std::string::npos) << sh.output;
  EXPECT_NE(sh.output.find("nosuchmethod"), std::string::npos) << sh.output;
}

// Issue 63, class 1: a results folder another run half-wrote. A point's render.json with a field of
// the wrong type ended `--pending` in nlohmann's type_error (exit 3); every field read back is checked:
// `--pending` lists the render again, `--collect` leaves its rows out, each saying which file and key.
TEST(BadInputCli, ASweepFolderAnotherRunHalfWroteCountsAsNotDone) {
  Image lit(8, 8);
  for (auto& p : lit.pixels) p = glm::vec3(0.5f, 0.25f, 0.125f);
  writeImage(lit, tmp("half_lit.exr"));
  const std::string file = tmp("half_written.json"), dir = tmp("half_written_out");
  std::filesystem::remove_all(dir);
  std::ofstream(file) << R"({"scenes": ["builtin:cornell"], "size": "8x8", "spp": 2, "checkpoints": [1],
    "reference": {"file": ")"
                      << tmp("half_lit.exr") << R"("}, "methods": [{"method": "direct"}]})";
  ASSERT_EQ(vgi("sweep " + file + " -o " + dir).code, 0);
  std::string stats;
  for (auto& e : std::filesystem::recursive_directory_iterator(dir))
    if (e.path().filename() == "render.json") stats = e.path().string();
  ASSERT_FALSE(stats.empty());
  const std::string checkpoint =
      std::filesystem::path(stats).replace_filename("render.spp00001.json").string();
  const nlohmann::json good = nlohmann::json::parse(std::ifstream(stats));
  const nlohmann::json goodCheckpoint = nlohmann::json::parse(std::ifstream(checkpoint));
  EXPECT_EQ(vgi("sweep " + file + " -o " + dir + " --pending").output, "");  // done: nothing pending
  for (const auto& [key, value] :
       std::vector<std::pair<std::string, nlohmann::json>>{{"spp_completed", "1"},
                                                           {"spp_completed", -4},
                                                           {"time_limited", "no"},
                                                           {"total_ms", "soon"},
                                                           {"timings_ms", {1, 2}},
                                                           {"sample_passes", {{{"a", 1}}}},
                                                           {"params", "none"},
                                                           {"gl_renderer", 3}}) {
    nlohmann::json bad = good;
    bad[key] = value;
    std::ofstream(stats) << bad.dump();
    const CliRun pending = vgi("sweep " + file + " -o " + dir + " --pending");
    EXPECT_EQ(pending.code, 0) << key << ": " << pending.output;
    EXPECT_EQ(pending.output.find("internal error"), std::string::npos) << pending.output;
    const bool countsAsNotDone = key == "spp_completed";  // (time_limited is read where spp falls short)
    if (countsAsNotDone) {
      EXPECT_NE(pending.output.find("render"), std::string::npos) << key << ": listed again\n"
                                                                  << pending.output;
      EXPECT_NE(pending.output.find("'" + key + "'"), std::string::npos) << pending.output;
    }
    const CliRun collect = vgi("sweep " + file + " -o " + dir + " --collect");
    EXPECT_EQ(collect.code, 0) << key << ": " << collect.output;
    EXPECT_EQ(collect.output.find("internal error"), std::string::npos) << collect.output;
    EXPECT_NE(collect.output.find(stats), std::string::npos) << key << ": names the file\n" << collect.output;
    EXPECT_NE(collect.output.find("'" + key + "'"), std::string::npos) << collect.output;
  }
  std::ofstream(stats) << good.dump();
  // A checkpoint's stats and a frame of the wrong shape: that row is left out, saying why.
  for (const nlohmann::json& frames : {nlohmann::json("three"), nlohmann::json::array({7})}) {
    nlohmann::json bad = goodCheckpoint;
    bad["frames"] = frames;
    std::ofstream(checkpoint) << bad.dump();
    const CliRun collect = vgi("sweep " + file + " -o " + dir + " --collect");
    EXPECT_EQ(collect.code, 0) << collect.output;
    EXPECT_NE(collect.output.find(checkpoint), std::string::npos) << collect.output;
    EXPECT_NE(collect.output.find("1 rows"), std::string::npos) << collect.output;  // the last image's row
  }
  std::ofstream(checkpoint) << goodCheckpoint.dump();
  // A plain run renders the damaged point again and ends with every row.
  nlohmann::json bad = good;
  bad["spp_completed"] = "2";
  std::ofstream(stats) << bad.dump();
  const CliRun again = vgi("sweep " + file + " -o " + dir);
  EXPECT_EQ(again.code, 0) << again.output;
  EXPECT_NE(again.output.find("[1/1]"), std::string::npos) << again.output;
  EXPECT_NE(again.output.find("2 rows"), std::string::npos) << again.output;
  // What `bench motion` and `render --job` read: refused naming the file and the key.
  const std::string moving = tmp("half_moving.json");
  std::ofstream(moving) << R"({"method": "direct", "width": 8, "height": 8,
      "frames": [{"timings_ms": {"a": 1}}, {"timings_ms": "fast"}]})";
  expectRefused(vgi("bench motion " + moving + " " + moving), {moving, "timings_ms"});
  std::ofstream(moving)
      << R"({"method": "direct", "width": 8, "height": 8, "frames": [{"timings_ms": {"a": 1}}, 5]})";
  expectRefused(vgi("bench motion " + moving + " " + moving), {moving, "timings_ms"});
  nlohmann::json job = good;
  job["job"]["spp"] = "1";
  std::ofstream(tmp("half_job.json")) << job.dump();
  expectRefused(vgi("render --job " + tmp("half_job.json")), {tmp("half_job.json"), "'spp'", "\"1\""});
}

// Issue 63, class 2: the table scripts read vgi's own "undefined" (a metric with no value) and rows
// that are missing as such — a cell "undefined" or "—", never a traceback.
TEST(BadInputCli, TableScriptsReadUndefinedMetricsAndMissingRows) {
  const std::string scripts = dataPath("../../scripts");
  const std::string dir = tmp("undefined_tables");
  std::filesystem::create_directories(dir + "/points/p1");
  const nlohmann::json undefinedChannel = {{"relmse", "undefined"},          {"relmse_relative", "undefined"},
                                           {"rel_mae", "undefined"},         {"ssim", 1.0},
                                           {"energy", "undefined"},          {"leak", "undefined"},
                                           {"temporal_error", "undefined"},  {"change", "undefined"},
                                           {"change_reference", "undefined"}};
  auto row = [&](const std::string& label, const std::string& scene, const std::string& method) {
    return nlohmann::json{{"label", label},
                          {"scene", scene},
                          {"method", method},
                          {"role", "point"},
                          {"point", "p1"},
                          {"params", {{"voxels", 128}}},
                          {"spp", 1},
                          {"time_ms", 5.0},
                          {"sample_ms", 4.0},
                          {"setup_ms", 1.0},
                          {"git_revision", "abc"},
                          {"machine", "m"},
                          {"gl_renderer", "llvmpipe"},
                          {"image", undefinedChannel},
                          {"indirect", undefinedChannel}};
  };
  auto run = [&](const std::string& experiment, const nlohmann::json& rows, const std::string& script) {
    std::ofstream(dir + "/results.json")
        << nlohmann::json{{"experiment", experiment}, {"size", {8, 8}}, {"spp", 1}, {"rows", rows}}.dump();
    const CliRun r = test::shell("cd " + scripts + "/.. && python3 scripts/" + script + " " + dir);
    EXPECT_EQ(r.code, 0) << script << "\n" << r.output;
    EXPECT_EQ(r.output.find("Traceback"), std::string::npos) << script << "\n" << r.output;
    EXPECT_NE(r.output.find("undefined"), std::string::npos) << script << "\n" << r.output;
    return r;
  };
  const std::string bunny = "scenes/cornell-bunny.json", walk = "scenes/sibenik-walk.json";
  // Two labels, and the second without a Sibenik walk row (a missing row): "—".
  const nlohmann::json rows = {row("vct before", bunny, "vct"), row("vct before", walk, "vct"),
                               row("exact, seed 2", bunny, "reference"), row("vct after", bunny, "vct")};
  run("artefacts-remedies", rows, "artefacts_remedies_tables.py");
  const CliRun t = run("artefacts", rows, "artefacts_tables.py");
  EXPECT_NE(t.output.find("—"), std::string::npos) << t.output;
  std::ofstream(dir + "/points/p1/render.json")
      << R"({"timings_ms": {"svo_build": "undefined"}, "extra": {}})";
  run("svo", {row("vct dense", bunny, "vct"), row("vct svo", bunny, "vct")}, "svo_tables.py");
  std::ofstream(dir + "/points/p1/render.json") << "[1, 2";
  const CliRun torn = test::shell("cd " + scripts + "/.. && python3 scripts/svo_tables.py " + dir);
  EXPECT_EQ(torn.code, 2) << torn.output;
  EXPECT_NE(torn.output.find("render.json"), std::string::npos) << torn.output;
  EXPECT_EQ(torn.output.find("Traceback"), std::string::npos) << torn.output;
}

// Issue 63, class 3: a light and a camera on keys at the ends of float's range, rendered between them:
// the light stands where the keys put it (the interpolation overflowed to inf / inf: a black image).
TEST(BadInputCli, KeysAtTheEndsOfFloatsRangeGiveTheLitImage) {
  const std::string stem = tmp("extreme_keys");
  const CliRun r = vgi("render --scene '" + dataPath("bad/extreme_key_times.json") +
                       "' --time 1e38 --size 16x16 --spp 1 --quiet -o " + stem + ".exr");
  expectRendered(r, stem);
  const nlohmann::json s = nlohmann::json::parse(std::ifstream(stem + ".json"));
  ASSERT_TRUE(s["lights"][0]["position"][0].is_number()) << s["lights"].dump();
  EXPECT_NEAR(s["lights"][0]["position"][0].get<double>(), 0.2 + 0.2 * 2.0 / 3.0, 1e-6);
  EXPECT_NEAR(s["camera"]["position"][2].get<double>(), -0.8 + 0.1 * 2.0 / 3.0, 1e-6);
  EXPECT_GT(test::meanOf(readImage(stem + ".exr")), 1e-3);  // lit
}

// Issue 63, class 4: vgi's environment variables. A value it cannot use is refused naming the variable
// and the value (VGI_CACHE_LIMIT_MB=0 and =2GB rendered with the default 2 GiB, without a word), or, where
// the run can go on, warned about once.
TEST(BadInputCli, EnvironmentVariablesAreRefusedOrWarnedAboutByName) {
  const std::string vgiPath = VGI_BINARY, out = " --size 8x8 --spp 1 --quiet -o " + tmp("env.exr");
  for (const char* v : {"0", "2GB", "-1", "", "1e3", " 5", "99999999999999999999"})
    expectRefused(test::shell("VGI_CACHE_LIMIT_MB='" + std::string(v) + "' " + vgiPath + " render" + out),
                  {"VGI_CACHE_LIMIT_MB", "'" + std::string(v) + "'"});
  EXPECT_EQ(test::shell("VGI_CACHE_LIMIT_MB=64 " + vgiPath + " render" + out).code, 0);
  expectRefused(test::shell("VGI_SHADER_DIR=" + tmp("") + " " + vgiPath + " render" + out),
                {"VGI_SHADER_DIR", tmp("")});
  expectRefused(test::shell("VGI_SHADER_DIR= " + vgiPath + " --version"), {"VGI_SHADER_DIR", "''"});
  // A cache folder that cannot be made: the render goes on, warned once, and is the cache-off image.
  const std::string blocker = tmp("env_cache_blocker");
  std::filesystem::remove_all(blocker);
  std::ofstream(blocker) << "a file";
  const CliRun cached =
      test::shell("VGI_CACHE_DIR=" + blocker + " " + vgiPath + " render --method voxelpath" + out);
  EXPECT_EQ(cached.code, 0) << cached.output;
  const size_t warned = cached.output.find("vgi: warning: the set-up cache folder '" + blocker + "'");
  EXPECT_NE(warned, std::string::npos) << cached.output;
  EXPECT_EQ(cached.output.find("vgi: warning: the set-up cache", warned + 1), std::string::npos)
      << cached.output;
  expectRefused(test::shell("VK_ICD_FILENAMES=/no/such/icd.json " + vgiPath + " render --gl zink" + out),
                {"VK_ICD_FILENAMES", "/no/such/icd.json"});
  // The scripts' own: gpu_bench.sh's VGI_SCENES.
  const CliRun scenes = test::shell("cd " + dataPath("../..") +
                                    " && VGI_SCENES=/no/such/scenes bash scripts/gpu_bench.sh --vgi " +
                                    vgiPath + " " + tmp("env_gpu_bench"));
  EXPECT_EQ(scenes.code, 2) << scenes.output;
  EXPECT_NE(scenes.output.find("VGI_SCENES '/no/such/scenes'"), std::string::npos) << scenes.output;
}

// Issue 63, class 5: an option's empty value. CLI11 read "--help-module=" as the option without a
// value and took the next argument for it (the message was about 16x16), and "--help-module ''" as
// not given (a render ran); each is refused naming the option.
TEST(BadInputCli, EmptyOptionValuesAreRefusedNamingTheOption) {
  for (const std::string& args :
       {std::string("render --help-module= --size 16x16"),
        std::string("render --help-module '' --size 16x16"), std::string("render --method= -o x.exr"),
        std::string("render --spp= -o x.exr"), std::string("render --scene '' -o x.exr"),
        std::string("render -o ''"), std::string("voxelize --voxelizer= --voxels 128"),
        std::string("bench traverse --tracers="), std::string("compare --reference= --spp 1"),
        std::string("view --script=")}) {
    const std::string option =
        args.substr(args.find(" -") + 1, args.find_first_of("= ", args.find(" -") + 1) - args.find(" -") - 1);
    expectRefused(vgi(args), {option + " was given an empty value"});
  }
  expectRefused(vgi("diff '' b.exr"), {"empty argument"});
  expectRefused(vgi("sweep '' -o " + tmp("empty_sweep")), {"empty argument"});
  // A flag's '=' is CLI11's business; a value that is not empty is what it was.
  EXPECT_EQ(vgi("render --method=direct --size 8x8 --spp 1 --quiet -o " + tmp("eq.exr")).code, 0);
}

}  // namespace vgi
