// The `vgi` command as a user runs it: exit codes, messages, outputs.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "apps/cli_util.h"
#include "core/json_text.h"
#include "illum/framework/render_options.h"

namespace vgi {

using test::CliRun;
using test::dataPath;
using test::tmp;
using test::vgi;

TEST(Cli, RenderWritesExrPngAndStats) {
  CliRun r =
      vgi("render --scene builtin:cornell --method reference --set integrator=direct --size 32x24 --spp 2 "
          "--quiet -o " +
          tmp("cli.exr") + " --stats " + tmp("cli_stats.json"));
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(tmp("cli.png")));
  nlohmann::json s = nlohmann::json::parse(std::ifstream(tmp("cli.json")));
  EXPECT_EQ(s["width"], 32);
  EXPECT_EQ(s["height"], 24);
  EXPECT_EQ(s["params"]["integrator"], "direct");
  EXPECT_TRUE(std::filesystem::exists(tmp("cli_stats.json")));
}

// An animation: one image pair per frame (AOVs too), one stats JSON listing them with per-frame stats.
TEST(Cli, RenderFramesWritesNumberedImagesAndOneStatsFile) {
  CliRun r =
      vgi("render --scene builtin:cornell --method nearfield --size 16x16 --spp 1 --frames 2 --time-step 0.5 "
          "--aov indirect --quiet -o " +
          tmp("anim.exr"));
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* f :
       {"anim_0000.exr", "anim_0000.png", "anim_0001.exr", "anim_0001.png", "anim_0001.indirect.exr"})
    EXPECT_TRUE(std::filesystem::exists(tmp(f))) << f;
  EXPECT_FALSE(std::filesystem::exists(tmp("anim.exr")));
  nlohmann::json s = nlohmann::json::parse(std::ifstream(tmp("anim.json")));
  ASSERT_EQ(s["frames"].size(), 2u);
  EXPECT_EQ(s["frames"][1]["time"], 0.5);
  EXPECT_EQ(s["frames_completed"], 2);
  EXPECT_EQ(s["outputs"].size(), 8u);  // 2 frames × (image, indirect) × (exr, png)
  CliRun bad = vgi("render --frames 0 --size 8x8 -o " + tmp("x.exr"));
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.output.find("--frames 0"), std::string::npos) << bad.output;
  CliRun nan = vgi("render --frames 2 --time-step nan --size 8x8 -o " + tmp("x.exr"));
  EXPECT_EQ(nan.code, 2);
  EXPECT_NE(nan.output.find("--time-step"), std::string::npos) << nan.output;
}

// Speed against error in one command: nearfield against reference
// integrator=nearfield with the same (resolved) radius and env.
TEST(Cli, CompareRendersTheExactCounterpartWithTheSameParameters) {
  CliRun r =
      vgi("compare --scene builtin:cornell --method nearfield --set env=false --size 24x24 --spp 2 "
          "--ref-spp 64 --relative-epsilon 0.1 --quiet -o " +
          tmp("cmp.exr"));
  ASSERT_EQ(r.code, 0) << r.output;
  nlohmann::json s = nlohmann::json::parse(std::ifstream(tmp("cmp.json")));
  const std::vector<std::string> set = s["exact"]["set"];
  ASSERT_EQ(set.size(), 4u);
  EXPECT_EQ(set[0], "integrator=nearfield");
  EXPECT_FLOAT_EQ(std::stof(set[1].substr(7)), s["method_params"]["radius"].get<float>());
  EXPECT_EQ(set[2], "env=false");
  EXPECT_EQ(set[3], "glossy=direct");  // the model's omissions: its indirect light is reflected diffusely
  for (const char* k : {"image", "direct", "indirect"}) {
    EXPECT_TRUE(s["error"].contains(k)) << k;
    // Split by default: total, model and approximation, the last the same as "error".
    for (const char* e : {"total", "model", "approximation"})
      EXPECT_TRUE(s["split"][k].contains(e)) << k << e;
    EXPECT_EQ(s["split"][k]["approximation"], s["error"][k]);
  }
  EXPECT_EQ(s["full"]["method"], "reference_gl");
  EXPECT_EQ(s["full"]["set"], nlohmann::json({"integrator=path", "env_channel=indirect"}));
  EXPECT_EQ(s["full"]["seed"], s["seed"].get<int>() + 2);
  EXPECT_NE(r.output.find("approx"), std::string::npos) << r.output;
  EXPECT_LT(s["error"]["image"]["rel_mae"].get<double>(), 0.3);  // 24², 2 frames: measured 0.15
  EXPECT_GT(s["time"]["method_ms_per_frame"].get<double>(), 0.0);
  EXPECT_GT(s["time"]["method_setup_ms"].get<double>(), 0.0);  // voxelization, RSMs: not per frame
  // ε scaled to each channel's mean: the indirect channel's is far below the default 0.01.
  EXPECT_LT(s["error"]["indirect"]["relmse_epsilon"].get<double>(), 1e-3);
  for (const char* k : {"rel_mae_rgb", "energy_rgb"}) EXPECT_EQ(s["error"]["indirect"][k].size(), 3u) << k;
  for (const char* f : {"cmp.nearfield.exr", "cmp.nearfield.indirect.exr", "cmp.exact.exr", "cmp.exact.json",
                        "cmp.full.exr", "cmp.full.indirect.exr", "cmp.full.json", "cmp.error.exr",
                        "cmp.error.indirect.exr", "cmp.error.indirect.png"})
    EXPECT_TRUE(std::filesystem::exists(tmp(f))) << f;
  nlohmann::json ex = nlohmann::json::parse(std::ifstream(tmp("cmp.exact.json")));
  EXPECT_EQ(ex["spp"], 64);
  EXPECT_EQ(ex["params"]["env"], false);
  // On the method's device by default (reference's GL twin), and it says so; --exact-device cpu: reference.
  EXPECT_EQ(s["exact"]["method"], "reference_gl");
  EXPECT_EQ(s["exact"]["device"], "gl");
  EXPECT_EQ(s["exact"]["same_device"], true);
  EXPECT_NE(r.output.find("same device"), std::string::npos) << r.output;
  CliRun cpu =
      vgi("compare --method voxel_ao --size 8x8 --spp 1 --ref-spp 1 --exact-device cpu --no-split "
          "--quiet -o " +
          tmp("c.exr"));
  ASSERT_EQ(cpu.code, 0) << cpu.output;
  nlohmann::json c = nlohmann::json::parse(std::ifstream(tmp("c.json")));
  EXPECT_FALSE(c.contains("split"));
  EXPECT_FALSE(std::filesystem::exists(tmp("c.full.exr")));
  EXPECT_EQ(c["exact"]["method"], "reference");
  EXPECT_EQ(c["exact"]["device"], "cpu");
  EXPECT_EQ(c["exact"]["same_device"], false);
  CliRun badDevice = vgi("compare --exact-device gpu --size 8x8 -o " + tmp("x.exr"));
  EXPECT_EQ(badDevice.code, 2);
  EXPECT_NE(badDevice.output.find("--exact-device"), std::string::npos) << badDevice.output;
  CliRun exact = vgi("compare --method reference --size 8x8 -o " + tmp("x.exr"));
  EXPECT_EQ(exact.code, 2);
  EXPECT_NE(exact.output.find("exactly"), std::string::npos) << exact.output;
  CliRun spp = vgi("compare --ref-spp 0 --size 8x8 -o " + tmp("x.exr"));
  EXPECT_EQ(spp.code, 2);
  EXPECT_NE(spp.output.find("--ref-spp 0"), std::string::npos) << spp.output;
}

// One serialization of a render job: every option renderArgs spells is parsed by the real `vgi render`
// into the same job (a renamed flag fails here, not in a sweep at run time), and the job JSON, given
// back with --job, is the same job again.
TEST(Cli, RenderArgsAndTheJobJsonRoundTripThroughTheCommandLine) {
  RenderOptions still;  // every option away from its default
  // Three delta lights, so that --light can move two of them by index, and a preset.
  const std::string threeLights = tmp("three_lights.json");
  std::ofstream(threeLights) << R"({"meshes": [{"path": ")" << dataPath("../../scenes/leak-rooms.obj")
                             << R"("}], "lights": [
    {"type": "point", "position": [0.5, 0.5, 0.5], "intensity": 1.0},
    {"type": "point", "position": [0.2, 0.5, 0.5], "intensity": 0.5},
    {"type": "point", "position": [0.8, 0.5, 0.5], "intensity": 0.5}],
    "presets": {"fast": {"diffuse_cones": "6"}}})";
  still.scene = threeLights;
  still.method = "vct";
  still.set = {"voxels=128", "aperture=50"};
  still.preset = "fast";
  still.width = 40;
  still.height = 30;
  still.spp = 7;
  still.seed = 9;
  still.threads = 2;
  still.time = 0.25f;
  still.gl = GlBackend::Osmesa;
  still.aovs = {"indirect", "ao"};
  still.accumulation = Accumulation::Plain;
  still.checkpoints = {1, 3};
  still.timeLimitS = 2.5;
  Camera c;
  c.position = {0.1f, 0.2f, 3.0f};
  c.target = {0.0f, 0.3f, 0.0f};
  c.up = {0.0f, 1.0f, 0.0f};
  c.fovYDeg = 33.0f;
  still.camera = c;
  still.lightPositions = {{0, {0.1f, 0.2f, 0.3f}}, {2, {-1.0f, 0.5f, 0.25f}}};
  still.progress = false;
  RenderOptions animation;
  animation.method = "nearfield";
  animation.frames = 3;
  animation.timeStep = 0.125f;
  for (const RenderOptions& o : {still, animation, RenderOptions{}}) {
    const nlohmann::json want = renderJobJson(o);
    std::string args;
    for (const std::string& a : renderArgs(o)) args += " " + shellQuote(a);
    CliRun r = vgi("render" + args + " --print-job");
    ASSERT_EQ(r.code, 0) << args << "\n" << r.output;
    EXPECT_EQ(parseJsonText(r.output, "--print-job"), want) << args;
    const std::string file = tmp("job.json");
    std::ofstream(file) << jsonText(want, 2);
    CliRun j = vgi("render --job " + file + " --print-job");
    ASSERT_EQ(j.code, 0) << j.output;
    EXPECT_EQ(parseJsonText(j.output, "--job"), want);
    EXPECT_EQ(renderJobJson(readRenderJob(want, "test")), want);
  }
  // --job gives the options: another render option beside it is refused by name.
  CliRun both = vgi("render --job " + tmp("job.json") + " --spp 4 --print-job");
  EXPECT_EQ(both.code, 2) << both.output;
  EXPECT_NE(both.output.find("--spp may not be given with it"), std::string::npos) << both.output;
  // A job's keys are typed and named.
  std::ofstream(tmp("bad_job.json")) << R"({"method": "direct", "spp": "many"})";
  CliRun bad = vgi("render --job " + tmp("bad_job.json") + " --print-job");
  EXPECT_EQ(bad.code, 2) << bad.output;
  EXPECT_NE(bad.output.find("'spp' = \"many\" must be an integer"), std::string::npos) << bad.output;
  std::ofstream(tmp("typo_job.json")) << R"({"methd": "direct"})";
  CliRun typo = vgi("render --job " + tmp("typo_job.json") + " --print-job");
  EXPECT_EQ(typo.code, 2) << typo.output;
  EXPECT_NE(typo.output.find("unknown key 'methd'"), std::string::npos) << typo.output;
}

TEST(Cli, BadArgumentsFailWithClearMessages) {
  CliRun a = vgi("render --set nosuch=1 --size 8x8 -o " + tmp("x.exr"));
  EXPECT_EQ(a.code, 2);
  EXPECT_NE(a.output.find("nosuch=1"), std::string::npos) << a.output;
  CliRun b = vgi("render --size 0x10 -o " + tmp("x.exr"));
  EXPECT_EQ(b.code, 2);
  EXPECT_NE(b.output.find("--size '0x10'"), std::string::npos) << b.output;
  std::ofstream(tmp("a_file")) << "x";
  CliRun c = vgi("render --size 8x8 -o " + tmp("a_file/x.exr"));
  EXPECT_EQ(c.code, 2);
  EXPECT_NE(c.output.find("cannot create folder"), std::string::npos) << c.output;
  CliRun d = vgi("render --bogus");
  EXPECT_EQ(d.code, 2);
  CliRun e = vgi("render --scene " + test::dataPath("bad/nan_vertex.obj") + " -o " + tmp("x.exr"));
  EXPECT_EQ(e.code, 2);
  EXPECT_NE(e.output.find("nan_vertex.obj"), std::string::npos) << e.output;
  CliRun f = vgi("render --method reference --set integrator=teleport -o " + tmp("x.exr"));
  EXPECT_EQ(f.code, 2);
  EXPECT_NE(f.output.find("teleport"), std::string::npos) << f.output;
}

TEST(Cli, DiffRefusesDifferentSizes) {
  ASSERT_EQ(
      vgi("render --method reference --set integrator=ao --size 8x8 --spp 1 --quiet -o " + tmp("a.exr")).code,
      0);
  ASSERT_EQ(
      vgi("render --method reference --set integrator=ao --size 8x9 --spp 1 --quiet -o " + tmp("b.exr")).code,
      0);
  CliRun same = vgi("diff --json " + tmp("a.exr") + " " + tmp("a.exr"));
  ASSERT_EQ(same.code, 0) << same.output;
  EXPECT_EQ(nlohmann::json::parse(same.output)["rmse"], 0.0);
  CliRun diff = vgi("diff " + tmp("a.exr") + " " + tmp("b.exr"));
  EXPECT_EQ(diff.code, 2);
  EXPECT_NE(diff.output.find("different sizes"), std::string::npos) << diff.output;
}

// FLIP in `vgi diff`: HDR-FLIP and LDR-FLIP for EXRs (pooled, with the maximum's pixel), LDR-FLIP
// alone for the PNGs `vgi render` writes beside them (sRGB-encoded), 0 for an image against itself,
// the map written, the viewing condition's options checked.
TEST(Cli, DiffReportsFlip) {
  for (const char* n : {"fa", "fb"})
    ASSERT_EQ(vgi(std::string("render --method reference --set integrator=ao --size 24x16 --spp ") +
                  (n[1] == 'a' ? "1" : "16") + " --quiet -o " + tmp(std::string(n) + ".exr"))
                  .code,
              0);
  CliRun exr = vgi("diff --json " + tmp("fa.exr") + " " + tmp("fb.exr") + " --flip-map " + tmp("fmap.png"));
  ASSERT_EQ(exr.code, 0) << exr.output;
  const nlohmann::json j = nlohmann::json::parse(exr.output);
  for (const char* mode : {"ldr", "hdr"}) {
    ASSERT_TRUE(j["flip"].contains(mode)) << exr.output;
    EXPECT_GT(j["flip"][mode]["mean"].get<double>(), 0.0);
    EXPECT_GE(j["flip"][mode]["max"].get<double>(), j["flip"][mode]["mean"].get<double>());
    EXPECT_EQ(j["flip"][mode]["max_pixel"].size(), 2u);
  }
  EXPECT_GE(j["flip"]["hdr"]["exposures"].get<int>(), 2);
  EXPECT_TRUE(std::filesystem::exists(tmp("fmap.png")));
  CliRun png = vgi("diff --json " + tmp("fa.png") + " " + tmp("fb.png"));
  ASSERT_EQ(png.code, 0) << png.output;
  const nlohmann::json p = nlohmann::json::parse(png.output);
  EXPECT_TRUE(p["flip"].contains("ldr"));
  EXPECT_FALSE(p["flip"].contains("hdr")) << "an sRGB PNG holds display values";
  CliRun same = vgi("diff --json " + tmp("fa.exr") + " " + tmp("fa.exr"));
  EXPECT_EQ(nlohmann::json::parse(same.output)["flip"]["hdr"]["max"], 0.0);
  CliRun off = vgi("diff --json --flip off " + tmp("fa.exr") + " " + tmp("fb.exr"));
  EXPECT_FALSE(nlohmann::json::parse(off.output).contains("flip"));
  for (const std::string& bad : {std::string("--flip-distance -1"), std::string("--flip-display-pixels 0"),
                                 std::string("--flip-distance 1e6"), std::string("--flip sometimes")}) {
    CliRun r = vgi("diff " + bad + " " + tmp("fa.exr") + " " + tmp("fb.exr"));
    EXPECT_EQ(r.code, 2) << bad;
    EXPECT_NE(r.output.find(bad.substr(0, bad.find(' '))), std::string::npos) << r.output;
  }
}

// `vgi diff --frames N` reads two animations as `vgi render --frames N -o X.exr` writes them and reports
// the temporal error (core/image_metrics.h) besides each frame's metrics.
TEST(Cli, DiffOfAnimationsReportsTheTemporalError) {
  const std::string common =
      "render --method reference --set integrator=ao --size 8x8 --spp 1 --frames 3 --quiet";
  ASSERT_EQ(vgi(common + " -o " + tmp("anim_a.exr")).code, 0);
  ASSERT_EQ(vgi(common + " -o " + tmp("anim_b.exr")).code, 0);
  CliRun same = vgi("diff --json --frames 3 " + tmp("anim_a.exr") + " " + tmp("anim_b.exr"));
  ASSERT_EQ(same.code, 0) << same.output;
  nlohmann::json j = nlohmann::json::parse(same.output);
  EXPECT_EQ(j["frames"], 3);
  EXPECT_EQ(j["temporal_error"], 0.0);  // the same seeds: the same frames
  EXPECT_EQ(j["per_frame"].size(), 3u);
  // One frame of A brightened: A changes twice (up, then down), B not at all.
  Image f1 = readImage(tmp("anim_a_0001.exr"));
  for (auto& p : f1.pixels) p += glm::vec3(0.5f);
  writeImage(f1, tmp("anim_a_0001.exr"));
  CliRun flicker = vgi("diff --json --frames 3 " + tmp("anim_a.exr") + " " + tmp("anim_b.exr"));
  ASSERT_EQ(flicker.code, 0) << flicker.output;
  double levelB = 0;
  for (int t : {1, 2})
    for (auto& p : readImage(tmp("anim_b_000" + std::to_string(t) + ".exr")).pixels)
      levelB += p.x + p.y + p.z;
  EXPECT_NEAR(nlohmann::json::parse(flicker.output)["temporal_error"].get<double>(),
              2 * 0.5 * 64 * 3 / levelB, 1e-4);
  CliRun text = vgi("diff --frames 3 " + tmp("anim_a.exr") + " " + tmp("anim_b.exr"));
  EXPECT_NE(text.output.find("temporal error"), std::string::npos) << text.output;
  CliRun missing = vgi("diff --frames 4 " + tmp("anim_a.exr") + " " + tmp("anim_b.exr"));
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.output.find("anim_a_0003.exr"), std::string::npos) << missing.output;
  CliRun image =
      vgi("diff --frames 3 --image " + tmp("e.exr") + " " + tmp("anim_a.exr") + " " + tmp("anim_b.exr"));
  EXPECT_EQ(image.code, 2) << image.output;
  // An output of each frame (anim_c_0000.indirect.exr …) with --aov.
  ASSERT_EQ(vgi("render --method nearfield --size 8x8 --spp 1 --frames 2 --quiet --aov indirect -o " +
                tmp("anim_c.exr"))
                .code,
            0);
  CliRun aov = vgi("diff --json --frames 2 --aov indirect " + tmp("anim_c.exr") + " " + tmp("anim_c.exr"));
  ASSERT_EQ(aov.code, 0) << aov.output;
  EXPECT_EQ(nlohmann::json::parse(aov.output)["temporal_error"], 0.0);
  EXPECT_EQ(vgi("diff --aov indirect " + tmp("anim_a.exr") + " " + tmp("anim_b.exr")).code, 2);
}

// The stats' memory is measured once the resources exist: their reported bytes, summed, beside the
// process's growth since before they were built (core/gpu_memory.h).
TEST(Cli, StatsMeasureMemoryAfterTheResourcesAreBuilt) {
  ASSERT_EQ(vgi("render --method nearfield --size 16x16 --spp 1 --quiet -o " + tmp("mem.exr")).code, 0);
  nlohmann::json s = nlohmann::json::parse(std::ifstream(tmp("mem.json")));
  double reported = 0;
  for (auto& [k, v] : s["extra"].items())
    if (v.is_object() && v.contains("bytes")) reported += v["bytes"].get<double>();
  const nlohmann::json& m = s["memory"];
  EXPECT_GT(reported, 1e6);  // light maps, grid, pyramid
  EXPECT_EQ(m["resources_bytes"].get<double>(), reported);
  EXPECT_GT(m["growth_bytes"].get<double>(), 0.0);
  // nearfield keeps only the gather kit's fix-up list: a 16-byte header and a word per pixel.
  EXPECT_EQ(m["method_bytes"].get<double>(), 16.0 + 4 * 16 * 16);
  // Its targets: the G-buffer (68 bytes per pixel), the film's image channel (48), the fix-ups (an
  // RGBA32F texture, 16), and at half resolution the gather's two RGBA32F textures (2 x 16 bytes per 4
  // pixels) and the edge mask (R32UI, 4).
  EXPECT_EQ(m["targets_bytes"].get<double>(), 16.0 * 16 * (68 + 48 + 16) + 8 * 8 * (2 * 16 + 4));
  EXPECT_EQ(m["reported_bytes"].get<double>(),
            reported + m["method_bytes"].get<double>() + m["targets_bytes"].get<double>());
  EXPECT_GT(m["growth_over_reported"].get<double>(), 0.1);
  EXPECT_GE(m["rss_bytes"].get<double>(), m["baseline"]["rss_bytes"].get<double>());
  // avg keeps its visibility grid and the VPLs' shadow atlas itself: counted as the method's bytes.
  ASSERT_EQ(vgi("render --method avg --set grid=32 --set vpls=64 --size 16x16 --spp 1 --quiet -o " +
                tmp("mem_avg.exr"))
                .code,
            0);
  const nlohmann::json a = nlohmann::json::parse(std::ifstream(tmp("mem_avg.json")));
  const auto atlas = a["extra"]["vpl_shadow_atlas"];
  EXPECT_EQ(a["memory"]["method_bytes"].get<double>(),
            32.0 * 32 * 32 * 32 + atlas[0].get<double>() * atlas[1].get<double>() * 4 + 64.0 * 3 * 64)
      << a["extra"].dump();
}

TEST(Cli, InfoAndHelpModule) {
  CliRun i = vgi("info --scene builtin:cornell --json");
  ASSERT_EQ(i.code, 0) << i.output;
  EXPECT_EQ(nlohmann::json::parse(i.output)["triangles"], 30);
  CliRun h = vgi("render --help-module reference");
  ASSERT_EQ(h.code, 0);
  EXPECT_NE(h.output.find("integrator"), std::string::npos);
  CliRun hd = vgi("render --help-module direct");
  EXPECT_NE(hd.output.find("shadow_res"), std::string::npos);
}

// Ctrl-C during a long render still writes what was accumulated.
TEST(Cli, InterruptWritesPartialImage) {
  CliRun r = vgi("render --method reference --set integrator=path --size 64x64 --spp 100000 --quiet -o " +
                 tmp("int.exr") + " & pid=$!; sleep 2; kill -INT $pid; wait $pid");
  ASSERT_EQ(r.code, 130) << r.output;  // interrupted: what was done is written, and the exit status says so
  nlohmann::json s = nlohmann::json::parse(std::ifstream(tmp("int.json")));
  EXPECT_TRUE(s["interrupted"].get<bool>());
  EXPECT_GT(s["spp_completed"].get<int>(), 0);
  EXPECT_LT(s["spp_completed"].get<int>(), 100000);
}

}  // namespace vgi

namespace vgi {
TEST(Cli, VoxelizeWritesStatsAndPicture) {
  auto r = vgi("voxelize --scene builtin:cornell --voxels 64x64x128 --voxelizer exact --stats " +
               tmp("vox.json") + " --dump " + tmp("vox.png"));
  ASSERT_EQ(r.code, 0) << r.output;
  nlohmann::json s = nlohmann::json::parse(std::ifstream(tmp("vox.json")));
  for (const char* k : {"voxelizer", "resolution", "voxels_set", "recall", "precision", "points",
                        "atlas_resolution", "timings_ms"})
    EXPECT_TRUE(s.contains(k)) << k;
  EXPECT_EQ(s["resolution"][2], 128);
  EXPECT_GT(s["voxels_set"].get<long>(), 0);
  EXPECT_TRUE(std::filesystem::exists(tmp("vox.png")));
  auto bad = vgi("voxelize --voxels 64x64x100");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.output.find("64x64x100"), std::string::npos) << bad.output;
  auto unknown = vgi("voxelize --voxelizer octree");
  EXPECT_EQ(unknown.code, 2);
  EXPECT_NE(unknown.output.find("octree"), std::string::npos);
}
}  // namespace vgi

namespace vgi {
TEST(Cli, VoxelizeBuildsOnlyTheRequestedValueGrids) {
  auto r = vgi("voxelize --voxels 64x64x128 --kind binary,albedo --stats " + tmp("kind.json") + " --dump " +
               tmp("kind.png"));
  ASSERT_EQ(r.code, 0) << r.output;
  nlohmann::json s = nlohmann::json::parse(std::ifstream(tmp("kind.json")));
  EXPECT_EQ(s["built"], nlohmann::json::array({"binary", "albedo"}));
  EXPECT_EQ(s["value_grids"]["albedo"]["cells"], s["voxels_set"]);
  EXPECT_TRUE(std::filesystem::exists(tmp("kind_albedo.png")));
  auto exact = vgi("voxelize --voxelizer exact --kind normal");
  EXPECT_EQ(exact.code, 2);
  EXPECT_NE(exact.output.find("--voxelizer atlas"), std::string::npos) << exact.output;
}
}  // namespace vgi

namespace vgi {
TEST(Cli, VoxelizeFramesReportPerFramePasses) {
  std::string scene = test::writeMovingTriangleScene("cli_frames");
  auto r = vgi("voxelize --scene " + scene + " --voxels 64x64x128 --frames 3 --time-step 0.5 --stats " +
               tmp("frames.json"));
  ASSERT_EQ(r.code, 0) << r.output;
  nlohmann::json s = nlohmann::json::parse(std::ifstream(tmp("frames.json")));
  ASSERT_EQ(s["frames"].size(), 3u);
  EXPECT_EQ(s["frames"][2]["time"], 1.0);
  for (const char* pass : {"copy", "insertion"})
    EXPECT_TRUE(s["frames"][1]["timings_ms"].contains(pass)) << pass;
  // The moving mesh's atlas was drawn once: a frame moves its points.
  EXPECT_FALSE(s["frames"][1]["timings_ms"].contains("atlas_render")) << s["frames"][1]["timings_ms"].dump();
  EXPECT_EQ(s["dynamic_meshes"], 1);
  EXPECT_GE(s["precision"].get<double>(), 0.9999);  // the grid of the last frame, against exact at its time
  auto bad = vgi("voxelize --frames 2 --time-step nan");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.output.find("--time-step"), std::string::npos) << bad.output;
}
}  // namespace vgi

namespace vgi {
TEST(Cli, BenchTraverseReportsEveryTracer) {
  CliRun r = vgi("bench traverse --voxels 128 --rays 3000 --repeat 1 --max-dist 0.2 --json --stats " +
                 tmp("bt.json"));
  ASSERT_EQ(r.code, 0) << r.output;
  nlohmann::json s = nlohmann::json::parse(std::ifstream(tmp("bt.json")));
  for (const char* t : {"hierarchical", "dda", "march", "embree"})
    for (const char* k : {"mrays_per_s", "agree_dda", "agree_embree_hit", "dist_err_p95_voxels"})
      EXPECT_TRUE(s["tracers"][t].contains(k)) << t << " " << k;
  EXPECT_EQ(s["tracers"]["hierarchical"]["agree_dda"], 1.0);
  EXPECT_EQ(s["tracers"]["embree"]["agree_embree_hit"], 1.0);
  EXPECT_EQ(s["tracers"]["hierarchical"]["gl_equals_cpu"], true);
  EXPECT_EQ(s["resolution"], nlohmann::json({128, 128, 128}));
  // The exact BVH (tracer=bvh): Embree's hits, and GLSL == C++.
  EXPECT_EQ(s["tracers"]["bvh"]["agree_embree_hit"], 1.0);
  EXPECT_EQ(s["tracers"]["bvh"]["gl_equals_cpu"], true);
  EXPECT_EQ(s["bvh"]["triangles"], 30);
  // Per ray, what each shared kernel pays (the C++ build counts the rays the GLSL traced): mean and p99.
  for (const char* t : {"hierarchical", "dda", "march", "bvh"})
    for (const char* k : {"steps", "fetches", "bytes", "climbs", "refines"}) {
      ASSERT_TRUE(s["tracers"][t]["counts"][k].contains("mean")) << t << " " << k;
      EXPECT_GE(s["tracers"][t]["counts"][k]["p99"].get<double>(), 0.0) << t << " " << k;
    }
  EXPECT_GT(s["tracers"]["hierarchical"]["counts"]["climbs"]["mean"].get<double>(), 0.0);
  EXPECT_LT(s["tracers"]["hierarchical"]["counts"]["fetches"]["mean"].get<double>(),
            s["tracers"]["dda"]["counts"]["fetches"]["mean"].get<double>());
  EXPECT_FALSE(s["tracers"]["embree"].contains("counts"));
  // A sweep of ray lengths: one entry each, and where the GLSL hierarchical and bvh tracers cross.
  CliRun w =
      vgi("bench traverse --voxels 128 --rays 2000 --repeat 1 --tracers hierarchical,bvh --max-dist "
          "0.01,0.3,inf --json --stats " +
          tmp("btw.json"));
  ASSERT_EQ(w.code, 0) << w.output;
  nlohmann::json sw = nlohmann::json::parse(std::ifstream(tmp("btw.json")));
  ASSERT_EQ(sw["lengths"].size(), 3u);
  EXPECT_EQ(sw["lengths"][2]["max_dist"], "inf");
  EXPECT_TRUE(sw["lengths"][1]["tracers"]["bvh"].contains("gl_mrays_per_s"));
  EXPECT_TRUE(sw.contains("crossover_max_dist"));
  CliRun a = vgi("bench traverse --max-dist -1");
  EXPECT_EQ(a.code, 2);
  EXPECT_NE(a.output.find("--max-dist -1"), std::string::npos) << a.output;
  CliRun b = vgi("bench traverse --tracers hierarchical,octree");
  EXPECT_EQ(b.code, 2);
  EXPECT_NE(b.output.find("octree"), std::string::npos) << b.output;
  CliRun c = vgi("voxelize --atlas-footprint 9");
  EXPECT_EQ(c.code, 2);
  EXPECT_NE(c.output.find("--atlas-footprint 9"), std::string::npos) << c.output;
}
}  // namespace vgi
