// vgi view (apps/viewer.h) under Xvfb with Mesa, as a script or a recording
// runs it: its screenshots equal `vgi render` of the same camera and
// parameters, a replayed script (orbit, change `rays`, switch to voxel_ao)
// gives what `vgi render` gives at each step, the panel lists the method's
// parameters, bad input is reported and the viewer keeps running, GL errors
// are 0.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "apps/cli_util.h"
#include "core/image.h"
#include "core/image_metrics.h"
#include "core/scene_loader.h"

namespace vgi {

using test::CliRun;
using test::tmp;
using test::vgi;

namespace {

bool haveXvfb() { return std::filesystem::exists("/usr/bin/xvfb-run"); }

// `vgi view …` in a fresh Xvfb server. The exit code is vgi's, written out by the shell inside:
// xvfb-run's own status is 5 when removing its temporary folder races with the server's exit,
// which happens after a command that fails at once. ctest runs each test in its own process, in
// parallel, so the script's name carries the test's name: a counter alone starts at 1 in every process
// and two tests overwrote each other's script.
CliRun underXvfb(const std::string& args) {
  static int runs = 0;
  const std::string script =
      tmp(std::string("xvfb_") + testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
          std::to_string(++runs) + ".sh");
  std::ofstream(script) << VGI_BINARY << " view " << args << " 2>&1\necho \"vgi-exit=$?\"\n";
  const std::string cmd = "/usr/bin/xvfb-run -a -s '-screen 0 1280x1024x24' /bin/sh " + script + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  for (size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
  const int status = pclose(p);
  const size_t at = out.rfind("vgi-exit=");
  if (at != std::string::npos) return {std::atoi(out.c_str() + at + 9), out.substr(0, at)};
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};  // the server did not start
}

ImageDiff difference(const std::string& a, const std::string& b) {
  return compareImages(readImage(a), readImage(b), a, b, DiffOptions{});
}

// An empty folder under the tests' temp folder.
std::string freshDir(const std::string& name) {
  const std::string dir = tmp(name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

nlohmann::json stats(const std::string& json) { return nlohmann::json::parse(std::ifstream(json)); }

// Screenshot DIR/NAME.exr equals `vgi render` of the command its stats give, bit for bit.
void expectSameAsRender(const std::string& dir, const std::string& name) {
  const std::string cmd = stats(dir + "/" + name + ".json")["command"].get<std::string>();
  CliRun r = vgi(cmd.substr(4) + " --quiet -o " + dir + "/" + name + "_again.exr");
  ASSERT_EQ(r.code, 0) << cmd << "\n" << r.output;
  EXPECT_EQ(difference(dir + "/" + name + ".exr", dir + "/" + name + "_again.exr").relMae, 0.0)
      << name << ": bit-identical to " << cmd;
  // The same from the screenshot's stats JSON as a job.
  CliRun j = vgi("render --job " + dir + "/" + name + ".json -o " + dir + "/" + name + "_job.exr");
  ASSERT_EQ(j.code, 0) << j.output;
  EXPECT_EQ(difference(dir + "/" + name + ".exr", dir + "/" + name + "_job.exr").relMae, 0.0)
      << name << ": bit-identical from --job";
}

// Whether the viewer kept `resource` across the change before screenshot DIR/NAME.
bool kept(const std::string& dir, const std::string& name, const char* resource) {
  const nlohmann::json list = stats(dir + "/" + name + ".json")["viewer"]["resources_kept"];
  return std::find(list.begin(), list.end(), resource) != list.end();
}

}  // namespace

// --frames 16 --screenshot of the Cornell box with nearfield equals vgi render --spp 16 of the same view.
TEST(View, FramesScreenshotEqualsRender) {
  if (!haveXvfb()) GTEST_FAIL() << "/usr/bin/xvfb-run is missing: scripts/setup.sh installs xvfb";
  const std::string shot = tmp("view_frames.exr"), ref = tmp("view_frames_ref.exr");
  CliRun v = underXvfb("--size 64x64 --frames 16 --screenshot " + shot);
  ASSERT_EQ(v.code, 0) << v.output;
  EXPECT_NE(v.output.find("0 GL errors"), std::string::npos) << v.output;
  ASSERT_EQ(vgi("render --size 64x64 --spp 16 --quiet -o " + ref).code, 0);
  const ImageDiff d = difference(shot, ref);
  EXPECT_LT(d.relMse, 0.001);
  EXPECT_EQ(d.relMae, 0.0) << "the same samples in the same order: bit-identical";
  const nlohmann::json s = stats(tmp("view_frames.json"));
  EXPECT_EQ(s["spp"], 16);
  EXPECT_EQ(s["method"], "nearfield");
  EXPECT_NE(s["gl_renderer"].get<std::string>().find("llvmpipe"), std::string::npos) << s["gl_renderer"];
  EXPECT_EQ(s["viewer"]["gl_errors"], 0);
}

// The temporal filter in the viewer: after the camera moved, the first sample is blended with the
// frames before (reprojected), nearer the converged view than that sample alone; standing, the samples
// refine it and from 1/alpha samples on the image is their mean, bit for bit `vgi render` again.
TEST(View, AMovingCameraIsFilteredOverTimeAndAStandingOneConverges) {
  if (!haveXvfb()) GTEST_FAIL() << "/usr/bin/xvfb-run is missing: scripts/setup.sh installs xvfb";
  const std::string dir = freshDir("view_temporal");
  std::ofstream(dir + "/script.json") << R"([{"frames": 8}, {"orbit": [4, 0]}, {"frames": 1},
    {"screenshot": ")" << dir << R"(/moved.exr"}, {"frames": 9}, {"screenshot": ")"
                                      << dir << R"(/stood.exr"}])";
  CliRun v = underXvfb("--size 48x48 --script " + dir + "/script.json");
  ASSERT_EQ(v.code, 0) << v.output;
  const nlohmann::json moved = stats(dir + "/moved.json"), stood = stats(dir + "/stood.json");
  EXPECT_TRUE(moved["viewer"]["filtered_over_time"].get<bool>());
  EXPECT_EQ(moved["spp"], 1);
  EXPECT_FALSE(stood["viewer"]["filtered_over_time"].get<bool>());
  EXPECT_EQ(stood["spp"], 10);
  expectSameAsRender(dir, "stood");
  // The moved view alone (its command: 1 sample) and converged (64).
  const std::string cmd = moved["command"].get<std::string>().substr(4);
  ASSERT_EQ(vgi(cmd + " --quiet -o " + dir + "/alone.exr").code, 0);
  std::string converged = cmd;
  const size_t spp = converged.find("--spp '1'");
  ASSERT_NE(spp, std::string::npos) << cmd;
  converged.replace(spp, 9, "--spp '64'");
  ASSERT_EQ(vgi(converged + " --quiet -o " + dir + "/converged.exr").code, 0);
  const double filtered = difference(dir + "/moved.exr", dir + "/converged.exr").relMse,
               alone = difference(dir + "/alone.exr", dir + "/converged.exr").relMse;
  EXPECT_LT(filtered, 0.8 * alone) << "filtered " << filtered << ", the sample alone " << alone;
}

// A script: orbit, rays=8, 4 frames, screenshot; bad input (a value out of range, an unknown method, a
// scene that does not load) is reported and the viewer keeps running; voxel_ao, 4 frames, screenshot.
// Each screenshot's JSON carries the `vgi render` command that renders it again, and it does.
TEST(View, ScriptReplaysLikeRenderAndSurvivesBadInput) {
  if (!haveXvfb()) GTEST_FAIL() << "/usr/bin/xvfb-run is missing: scripts/setup.sh installs xvfb";
  const std::string dir = freshDir("view_script");
  const std::string script = dir + "/script.json";
  std::ofstream(script) << R"([{"orbit": [25, 10]}, {"set": {"rays": 8}}, {"frames": 4},
    {"screenshot": ")" << dir
                        << R"(/nf.exr"},
    {"set": {"rays": 0}}, {"method": "nearfeld"}, {"scene": "/nonexistent/scene.obj"}, {"frames": 1},
    {"method": "voxel_ao"}, {"frames": 4}, {"screenshot": ")"
                        << dir << R"(/ao.exr"}, {"window_screenshot": ")" << dir << R"(/window.png"}])";
  CliRun v = underXvfb("--size 48x48 --script " + script);
  ASSERT_EQ(v.code, 0) << v.output;
  for (const char* needle :
       {"rays", "out of range", "nearfeld", "/nonexistent/scene.obj", "3 errors reported", "0 GL errors"})
    EXPECT_NE(v.output.find(needle), std::string::npos) << needle << " in " << v.output;

  for (const char* name : {"nf", "ao"}) {
    const nlohmann::json s = stats(dir + "/" + name + ".json");
    // The command that renders it again (camera, parameters, samples), written to another file.
    std::string cmd = s["command"].get<std::string>();
    ASSERT_EQ(cmd.rfind("vgi render ", 0), 0u) << cmd;
    const std::string again = dir + "/" + name + "_render.exr";
    CliRun r = vgi(cmd.substr(4) + " --quiet -o " + again);
    ASSERT_EQ(r.code, 0) << cmd << "\n" << r.output;
    const ImageDiff d = difference(dir + "/" + name + ".exr", again);
    EXPECT_LT(d.relMse, 0.001) << name;
    EXPECT_EQ(d.relMae, 0.0) << name << ": bit-identical";
    EXPECT_EQ(s["spp"], 4);
    EXPECT_EQ(s["viewer"]["gl_errors"], 0);
  }
  const nlohmann::json nf = stats(dir + "/nf.json"), ao = stats(dir + "/ao.json");
  EXPECT_EQ(nf["method"], "nearfield");
  EXPECT_EQ(nf["params"]["rays"], 8);
  EXPECT_EQ(ao["method"], "voxel_ao");
  ASSERT_EQ(vgi("render --method direct --size 4x4 --spp 1 --quiet -o " + dir + "/home.exr").code, 0);
  EXPECT_NE(nf["camera"]["option"], stats(dir + "/home.json")["camera"]["option"])
      << "the orbit moved the camera";
  // The panel lists every parameter of the method shown.
  for (const char* k : {"rays", "radius", "voxels", "voxelizer", "resolution", "blur"})
    EXPECT_NE(std::find(nf["viewer"]["panel_parameters"].begin(), nf["viewer"]["panel_parameters"].end(), k),
              nf["viewer"]["panel_parameters"].end())
        << k << " in " << nf["viewer"]["panel_parameters"].dump();
  EXPECT_EQ(ao["viewer"]["panel_parameters"].size(), ao["params"].size()) << ao["params"].dump();
  EXPECT_GT(std::filesystem::file_size(dir + "/window.png"), 5000u) << "the window, panel included";
  // The image fills the area beside the panel: a square of the panel's height (720), scaled up from
  // 48×48, so almost none of the area is the window's background (grey 0.1, sRGB-decoded ~0.01).
  const Image window = readImage(dir + "/window.png");
  EXPECT_EQ(window.width, 720 + 360);
  EXPECT_EQ(window.height, 720);
  size_t background = 0;
  for (int y = 0; y < window.height; ++y)
    for (int x = 0; x < 720 && x < window.width; ++x) {
      const glm::vec3 c = window.pixels[size_t(y) * size_t(window.width) + size_t(x)];
      background += glm::all(glm::lessThan(glm::abs(c - glm::vec3(0.0100228f)), glm::vec3(2e-3f)));
    }
  EXPECT_LT(background, size_t(720 * 720 / 50)) << "pixels of the image area left as background";
}

// A scene that loads but whose resources cannot be built (400 point lights need more light-map faces
// than the GL allows) gives way to the last scene that rendered, as an unbuildable setting does; it
// once left a half-built job ("internal: a method read a GridBox it did not declare", "nothing
// rendered yet", exit 0).
TEST(View, AScriptKeepsTheLastSceneThatRendered) {
  if (!haveXvfb()) GTEST_FAIL() << "/usr/bin/xvfb-run is missing: scripts/setup.sh installs xvfb";
  const std::string dir = freshDir("view_unbuildable");
  {
    std::ofstream scene(dir + "/many_lights.json");
    scene << R"({"meshes": [{"path": "builtin:cornell"}], "lights": [)";
    for (int i = 0; i < 400; ++i)
      scene << (i ? "," : "") << R"({"type": "point", "intensity": 0.01, "position": [)" << 0.1 + 0.002 * i
            << ", 0.4, 0.3]}";
    scene << "]}";
  }
  std::ofstream(dir + "/script.json")
      << R"([{"frames": 1}, {"scene": ")" << dir << R"(/many_lights.json"}, {"frames": 2}, {"screenshot": ")"
      << dir << R"(/kept.exr"}])";
  CliRun v = underXvfb("--size 24x24 --script " + dir + "/script.json");
  ASSERT_EQ(v.code, 0) << v.output;
  for (const char* needle : {"2400 light-map faces", "kept the previous scene (builtin:cornell)"})
    EXPECT_NE(v.output.find(needle), std::string::npos) << needle << " in " << v.output;
  for (const char* wrong : {"internal", "nothing rendered yet"})
    EXPECT_EQ(v.output.find(wrong), std::string::npos) << wrong << " in " << v.output;
  const nlohmann::json s = stats(dir + "/kept.json");
  EXPECT_EQ(s["scene"], "builtin:cornell");
  EXPECT_GE(s["spp"].get<int>(), 1);
}

// Ctrl-C: the viewer stops, still writes the screenshot of what it accumulated, and exits 130.
TEST(View, CtrlCWritesWhatWasAccumulatedAndExits130) {
  if (!haveXvfb()) GTEST_FAIL() << "/usr/bin/xvfb-run is missing: scripts/setup.sh installs xvfb";
  const std::string shot = tmp("view_sigint.exr");
  std::filesystem::remove(shot);
  // SIGINT to the viewer alone (a terminal's Ctrl-C would also reach Xvfb here, not a real display).
  CliRun r = test::shell("xvfb-run -a sh -c '" + std::string(VGI_BINARY) +
                         " view --method reference --set integrator=direct --size 32x32 --frames 1000000 "
                         "--screenshot " +
                         shot + " & pid=$!; sleep 5; kill -INT $pid; wait $pid; echo rc=$?'");
  EXPECT_NE(r.output.find("rc=130"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("interrupted"), std::string::npos) << r.output;
  ASSERT_TRUE(std::filesystem::exists(shot)) << r.output;
  for (const glm::vec3& p : readImage(shot).pixels) ASSERT_TRUE(std::isfinite(p.x));
}

// A setting whose resources cannot be built (a grid the atlas cannot fit; an AVG beyond the
// device's largest storage buffer) keeps the setting before it, which goes on rendering: the next screenshot is of it, and is
// the image `vgi render` makes with the kept parameters.
TEST(View, ASettingThatCannotBeBuiltKeepsThePreviousOne) {
  if (!haveXvfb()) GTEST_FAIL() << "/usr/bin/xvfb-run is missing: scripts/setup.sh installs xvfb";
  const std::string dir = freshDir("view_keep_previous");
  const std::string script = dir + "/script.json";
  std::ofstream(script) << "[{\"frames\": 1}, {\"set\": {\"voxels\": \"8192x8192x128\"}}, {\"frames\": 2}, "
                        << "{\"screenshot\": \"" << dir
                        << "/kept.exr\"}, {\"method\": \"avg\"}, {\"frames\": 1}, "
                        << "{\"set\": {\"grid\": 256}}, {\"frames\": 2}, {\"screenshot\": \"" << dir
                        << "/avg.exr\"}]";
  CliRun v = underXvfb("--size 32x32 --script " + script);
  ASSERT_EQ(v.code, 0) << v.output;
  EXPECT_NE(v.output.find("atlas"), std::string::npos) << v.output;
  EXPECT_NE(v.output.find("kept the previous setting"), std::string::npos) << v.output;
  EXPECT_EQ(v.output.find("internal"), std::string::npos) << v.output;
  EXPECT_EQ(v.output.find("nothing rendered yet"), std::string::npos) << v.output;
  const nlohmann::json kept = stats(dir + "/kept.json");
  EXPECT_EQ(kept["params"]["voxels"], "128") << kept.dump();
  EXPECT_EQ(kept["method"], "nearfield");
  const nlohmann::json avg = stats(dir + "/avg.json");  // grid 256 needs a larger SSBO than llvmpipe's
  EXPECT_EQ(avg["method"], "avg");
  EXPECT_EQ(avg["params"]["grid"], 64);
  for (const char* name : {"kept", "avg"}) {
    CliRun r = vgi(stats(dir + "/" + name + ".json")["command"].get<std::string>().substr(4) +
                   " --quiet -o " + dir + "/" + name + "_render.exr");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(difference(dir + "/" + name + ".exr", dir + "/" + name + "_render.exr").relMae, 0.0) << name;
  }
}

// What a script or the command line gets wrong is refused before the window opens, naming it.
TEST(View, BadInputIsRefusedWithItsName) {
  if (!haveXvfb()) GTEST_FAIL() << "/usr/bin/xvfb-run is missing: scripts/setup.sh installs xvfb";
  CliRun unknown = underXvfb("--method nearfeld --frames 1 --screenshot " + tmp("v.exr"));
  EXPECT_EQ(unknown.code, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("nearfeld"), std::string::npos) << unknown.output;
  CliRun scene = underXvfb("--scene /nonexistent/s.obj --frames 1 --screenshot " + tmp("v.exr"));
  EXPECT_EQ(scene.code, 2) << scene.output;
  EXPECT_NE(scene.output.find("/nonexistent/s.obj"), std::string::npos) << scene.output;
  const std::string bad = tmp("view_bad_script.json");
  std::ofstream(bad) << R"([{"frames": 1}, {"orbitt": [1, 2]}])";
  CliRun script = underXvfb("--script " + bad);
  EXPECT_EQ(script.code, 2) << script.output;
  EXPECT_NE(script.output.find("orbitt"), std::string::npos) << script.output;
  EXPECT_NE(script.output.find("event 1"), std::string::npos) << script.output;
  std::ofstream(bad) << R"([{"orbit": [1, "x"]}])";
  script = underXvfb("--script " + bad);
  EXPECT_EQ(script.code, 2) << script.output;
  EXPECT_NE(script.output.find("orbit"), std::string::npos) << script.output;
  // Every field typed, named by event and key (a list as a parameter value once gave no event).
  for (const char* e : {R"({"set": {"rays": [1]}})", R"({"method": 5})", R"({"frames": "x"})",
                        R"({"screenshot": 3})", R"({"set": {"radius": {"a": 1}}})"}) {
    std::ofstream(bad) << "[" << e << "]";
    script = underXvfb("--script " + bad);
    EXPECT_EQ(script.code, 2) << e << ": " << script.output;
    EXPECT_NE(script.output.find("event 0"), std::string::npos) << e << ": " << script.output;
    EXPECT_NE(script.output.find(bad), std::string::npos) << e << ": " << script.output;
  }
  // Finite as doubles but not as floats (once a black image and a '-nan' camera, or '--time inf').
  for (const char* e : {R"({"orbit": [1e300, 1e300]})", R"({"move": [0, 1e39, 0]})", R"({"time": 1e300})"}) {
    std::ofstream(bad) << "[" << e << "]";
    script = underXvfb("--script " + bad);
    EXPECT_EQ(script.code, 2) << e << ": " << script.output;
    EXPECT_NE(script.output.find("finite 32-bit float"), std::string::npos) << script.output;
  }
  CliRun shot = underXvfb("--frames 1 --screenshot " + tmp("v.txt"));
  EXPECT_EQ(shot.code, 2) << shot.output;
  EXPECT_NE(shot.output.find("v.txt"), std::string::npos) << shot.output;
  // Without a display (no Xvfb): a clear message, not a crash.
  CliRun nodisplay = vgi("view --frames 1 --screenshot " + tmp("v.exr") + " </dev/null");
  if (std::getenv("DISPLAY") == nullptr) {
    EXPECT_EQ(nodisplay.code, 2) << nodisplay.output;
    EXPECT_NE(nodisplay.output.find("xvfb-run"), std::string::npos) << nodisplay.output;
  }
}

// The light-map views, read back: the Cornell box's downward 90° spot light has cube faces; its −y face
// (3) sees the floor and the blocks' tops. With shadow_res = the image size, one texel per pixel: the
// up-facing texels (a third or more) lie at the floor's or a block top's height, and every texel's
// distance is its position's distance to the light, as the position and distance channels store them.
// A face or channel the maps do not have is reported and the viewer goes on; `direct` shows its
// (non-reflective) shadow maps, the same distances.
TEST(View, ShowsTheMethodsLightMaps) {
  if (!haveXvfb()) GTEST_FAIL() << "/usr/bin/xvfb-run is missing: scripts/setup.sh installs xvfb";
  const std::string dir = freshDir("view_rsm");
  const std::string script = dir + "/script.json";
  std::ofstream(script) << R"([{"show": "rsm.normal"}, {"light_face": 3}, {"frames": 1},
    {"screenshot": ")" << dir
                        << R"(/normal.exr"}, {"show": "rsm.position"}, {"frames": 1},
    {"screenshot": ")" << dir
                        << R"(/position.exr"}, {"show": "rsm.distance"}, {"frames": 1},
    {"screenshot": ")" << dir
                        << R"(/distance.exr"}, {"light_face": 6}, {"show": "rsm.flux"},
    {"method": "direct"}, {"set": {"shadow_res": 64}}, {"show": "shadow_map.distance"}, {"frames": 1},
    {"screenshot": ")" << dir
                        << R"(/shadow.exr"}])";
  CliRun v = underXvfb("--size 64x64 --set shadow_res=64 --script " + script);
  ASSERT_EQ(v.code, 0) << v.output;
  for (const char* needle : {"face 6 out of range", "rsm.flux", "2 errors reported", "0 GL errors"})
    EXPECT_NE(v.output.find(needle), std::string::npos) << needle << " in " << v.output;
  const Scene scene = loadScene("builtin:cornell");
  const Bounds b = scene.bounds();
  const float diag = b.diagonal();
  const glm::vec3 light = scene.lights.at(0).position;
  const Image normal = readImage(dir + "/normal.rsm.normal.exr"),
              pos = readImage(dir + "/position.rsm.position.exr"),
              dist = readImage(dir + "/distance.rsm.distance.exr"),
              shadow = readImage(dir + "/shadow.shadow_map.distance.exr");
  ASSERT_EQ(normal.width, 64) << "shadow_res 64 in a 64x64 image: one texel per pixel";
  int covered = 0, up = 0, badHeight = 0, badDistance = 0;
  for (size_t i = 0; i < normal.pixels.size(); ++i) {
    if (dist.pixels[i].x <= 0.0f) continue;  // no surface there
    ++covered;
    const glm::vec3 p = b.lo + pos.pixels[i] * (b.hi - b.lo);
    badDistance += std::abs(glm::length(p - light) - dist.pixels[i].x * diag) > 2e-3f * diag;
    EXPECT_EQ(shadow.pixels[i], dist.pixels[i]) << "texel " << i << ": the same distance in both maps";
    if (glm::length(normal.pixels[i] - glm::vec3(0.5f, 1.0f, 0.5f)) > 2e-3f) continue;
    ++up;
    const float h = p.y;  // the floor, the short block's top, the tall block's (core/builtin_scenes.cpp)
    badHeight += std::min({std::abs(h), std::abs(h - 0.165f), std::abs(h - 0.33f)}) > 1e-3f;
  }
  RecordProperty("covered", covered);
  RecordProperty("up", up);
  EXPECT_GT(covered, 64 * 64 / 2);
  EXPECT_GT(up, covered / 3);
  EXPECT_EQ(badHeight, 0);
  EXPECT_EQ(badDistance, 0);
  const nlohmann::json s = stats(dir + "/normal.json");
  EXPECT_EQ(s["viewer"]["light_face"], 3);
  EXPECT_EQ(s["viewer"]["shown"], "rsm.normal");
}

// Moving a light (the panel's drag, a script's "light" event): the light maps and the grid's radiance
// follow without voxelizing again, and the screenshot's command (with --light) renders the same image.
TEST(View, MovingALightRelightsAndKeepsTheGrid) {
  if (!haveXvfb()) GTEST_FAIL() << "/usr/bin/xvfb-run is missing: scripts/setup.sh installs xvfb";
  const std::string dir = freshDir("view_light");
  const std::string script = dir + "/script.json";
  std::ofstream(script) << R"([{"frames": 2}, {"screenshot": ")" << dir << R"(/before.exr"},
    {"light": "0=0.2,0.45,0.3"}, {"light": "3=0,0,0"}, {"frames": 10}, {"screenshot": ")"
                        << dir << R"(/after.exr"}])";
  CliRun v = underXvfb("--size 48x48 --script " + script);
  ASSERT_EQ(v.code, 0) << v.output;
  EXPECT_NE(v.output.find("1 errors reported"), std::string::npos) << "light 3 does not exist: " << v.output;
  const nlohmann::json before = stats(dir + "/before.json"), after = stats(dir + "/after.json");
  EXPECT_TRUE(before["timings_ms"].contains("pyramid")) << before["timings_ms"].dump();
  EXPECT_FALSE(after["timings_ms"].contains("pyramid"))
      << "the grid was kept: " << after["timings_ms"].dump();
  EXPECT_TRUE(after["timings_ms"].contains("rsm")) << "the light maps were rendered again";
  EXPECT_EQ(after["lights"][0]["option"], "0=0.200000003,0.449999988,0.300000012");
  EXPECT_GT(difference(dir + "/before.exr", dir + "/after.exr").relMse, 0.01) << "the light moved";
  const std::string cmd = after["command"].get<std::string>();
  ASSERT_NE(cmd.find("--light '0="), std::string::npos) << cmd;
  CliRun r = vgi(cmd.substr(4) + " --quiet -o " + dir + "/again.exr");
  ASSERT_EQ(r.code, 0) << cmd << "\n" << r.output;
  // 10 samples since the light moved (1/temporal_alpha): the mean, no longer the temporal filter's blend.
  EXPECT_FALSE(after["viewer"]["filtered_over_time"].get<bool>());
  EXPECT_EQ(difference(dir + "/after.exr", dir + "/again.exr").relMae, 0.0) << "bit-identical";
  for (const char* bad : {"5=0,0,0", "0=1,2", "x=1,2,3", "0=1,nan,2"}) {
    CliRun b =
        vgi(std::string("render --size 4x4 --spp 1 --quiet --light ") + bad + " -o " + dir + "/bad.exr");
    EXPECT_EQ(b.code, 2) << bad << ": " << b.output;
    EXPECT_NE(b.output.find("--light"), std::string::npos) << b.output;
  }
}

// A method switch or parameter change rebuilds only the resources that differ (RenderJob::makeResources,
// SceneResources::adopt): nearfield -> voxels -> nearfield keeps the grid and pyramid; vct with another
// shadow_res (radiance=atlas) keeps its grid and value grids but inserts their radiance again for the new
// shadow maps.
// Every screenshot still equals `vgi render` of its command, bit for bit.
TEST(View, SwitchingKeepsTheResourcesThatStayTheSame) {
  if (!haveXvfb()) GTEST_FAIL() << "/usr/bin/xvfb-run is missing: scripts/setup.sh installs xvfb";
  const std::string dir = freshDir("view_keep");
  const std::string script = dir + "/script.json";
  std::ofstream(script) << R"([{"frames": 1}, {"method": "voxels"}, {"frames": 1},
    {"screenshot": ")" << dir
                        << R"(/voxels.exr"}, {"method": "nearfield"}, {"frames": 2},
    {"screenshot": ")" << dir
                        << R"(/nf.exr"}, {"method": "vct"}, {"set": {"radiance": "atlas"}}, {"frames": 1},
    {"set": {"shadow_res": 256}},
    {"frames": 1}, {"screenshot": ")"
                        << dir << R"(/vct.exr"}])";
  CliRun v = underXvfb("--size 40x40 --script " + script);
  ASSERT_EQ(v.code, 0) << v.output;
  auto has = [](const nlohmann::json& list, const char* name) {
    return std::find(list.begin(), list.end(), name) != list.end();
  };
  for (const char* name : {"voxels", "nf", "vct"}) {
    const nlohmann::json s = stats(dir + "/" + name + ".json");
    const nlohmann::json kept = s["viewer"]["resources_kept"];
    EXPECT_TRUE(has(kept, "binary_grid") && has(kept, "or_mip_pyramid")) << name << ": " << kept.dump();
    EXPECT_FALSE(s["timings_ms"].contains("pyramid")) << name << ": " << s["timings_ms"].dump();
    expectSameAsRender(dir, name);
  }
  const nlohmann::json vct = stats(dir + "/vct.json");
  EXPECT_TRUE(has(vct["viewer"]["resources_kept"], "value_grids")) << vct["viewer"]["resources_kept"].dump();
  EXPECT_FALSE(has(vct["viewer"]["resources_kept"], "light_maps")) << "shadow_res changed: new maps";
  EXPECT_TRUE(vct["timings_ms"].contains("shadow_maps"));
}

// vct's radiance volume is a resource kind (cone_volume): a parameter of the march alone (step) keeps it,
// a setting of its injection (shadow_bias) keeps its allocation and injects again, and each screenshot
// equals `vgi render` of its command bit for bit (so the refilled volume is the one a fresh run builds).
TEST(View, VctKeepsItsConeVolumeAcrossMarchParameters) {
  if (!haveXvfb()) GTEST_FAIL() << "/usr/bin/xvfb-run is missing: scripts/setup.sh installs xvfb";
  const std::string dir = freshDir("view_cone_volume");
  const std::string script = dir + "/script.json";
  std::ofstream(script) << R"([{"method": "vct"}, {"frames": 1}, {"set": {"step": 0.5}}, {"frames": 1},
    {"screenshot": ")" << dir
                        << R"(/step.exr"}, {"set": {"shadow_bias": 2}}, {"frames": 1},
    {"screenshot": ")" << dir
                        << R"(/bias.exr"}])";
  CliRun v = underXvfb("--size 32x32 --script " + script);
  ASSERT_EQ(v.code, 0) << v.output;
  // step: the needs are the same, the job keeps all of its resources and nothing is built again.
  const nlohmann::json step = stats(dir + "/step.json");
  EXPECT_FALSE(step["timings_ms"].contains("vct_inject")) << step["timings_ms"].dump();
  EXPECT_FALSE(step["timings_ms"].contains("value_resolve")) << step["timings_ms"].dump();
  // shadow_bias: new needs (the volume's settings), the volume adopted by its key and injected again.
  EXPECT_TRUE(kept(dir, "bias", "cone_volume"));
  EXPECT_TRUE(kept(dir, "bias", "light_maps"));
  const nlohmann::json bias = stats(dir + "/bias.json");
  EXPECT_TRUE(bias["timings_ms"].contains("vct_inject")) << bias["timings_ms"].dump();
  for (const char* name : {"step", "bias"}) expectSameAsRender(dir, name);
}

// avg's occluders (resource kind "occluders") are kept when the resources change elsewhere (shadow_res: new
// light maps) and rebuilt when their own parameter changes (vpl_shadow_tolerance, the light maps kept);
// the screenshots equal `vgi render`.
TEST(View, AvgKeepsItsOccludersUntilTheirParametersChange) {
  if (!haveXvfb()) GTEST_FAIL() << "/usr/bin/xvfb-run is missing: scripts/setup.sh installs xvfb";
  const std::string dir = freshDir("view_occluders");
  const std::string script = dir + "/script.json";
  std::ofstream(script) << R"([{"method": "avg"}, {"frames": 1}, {"set": {"shadow_res": 256}}, {"frames": 1},
    {"screenshot": ")" << dir
                        << R"(/shadow_res.exr"}, {"set": {"vpl_shadow_tolerance": 0.004}}, {"frames": 1},
    {"screenshot": ")" << dir
                        << R"(/tolerance.exr"}])";
  CliRun v = underXvfb("--size 32x32 --script " + script);
  ASSERT_EQ(v.code, 0) << v.output;
  EXPECT_TRUE(kept(dir, "shadow_res", "occluders"));
  EXPECT_FALSE(kept(dir, "shadow_res", "light_maps"));
  EXPECT_FALSE(kept(dir, "tolerance", "occluders"));
  EXPECT_TRUE(kept(dir, "tolerance", "light_maps"));
  for (const char* name : {"shadow_res", "tolerance"}) expectSameAsRender(dir, name);
}

// --record writes every shown frame.
TEST(View, RecordWritesANumberedFrameSequence) {
  if (!haveXvfb()) GTEST_FAIL() << "/usr/bin/xvfb-run is missing: scripts/setup.sh installs xvfb";
  const std::string dir = tmp("view_record");
  std::filesystem::remove_all(dir);
  CliRun v = underXvfb("--size 32x32 --frames 3 --record " + dir + " --screenshot " + tmp("rec.exr"));
  ASSERT_EQ(v.code, 0) << v.output;
  for (const char* f : {"frame_00000.png", "frame_00001.png", "frame_00002.png"})
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + f)) << f;
  EXPECT_FALSE(std::filesystem::exists(dir + "/frame_00003.png"));
}

}  // namespace vgi
