// vgi sweep (experiments/sweep.h) as a user runs it: the shipped smoke experiment
// (two methods × two settings on a 32² Cornell box) renders, its CSV has one
// row per point and checkpoint, errors fall with the checkpoints, a second run
// renders nothing, a point whose render was killed is rendered again; bad
// experiment files are refused before anything renders.
#include "experiments/sweep.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "apps/cli_util.h"

namespace vgi {

using test::CliRun;
using test::tmp;
using test::vgi;

namespace {
const std::string kSmoke = std::string(VGI_TEST_DATA) + "/../../scenes/experiments/smoke.json";

std::vector<std::string> lines(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string l; std::getline(ss, l);)
    if (!l.empty()) out.push_back(l);
  return out;
}

size_t countOf(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
  return n;
}
}  // namespace

TEST(Sweep, SmokeExperimentRunsCollectsAndResumes) {
  const std::string dir = tmp("sweep_smoke");
  std::filesystem::remove_all(dir);
  // The command list: one reference per counterpart (nearfield's, voxel_ao's) and its convergence
  // render (the next seed), one render per point.
  CliRun list = vgi("sweep " + kSmoke + " -o " + dir + " --print-commands");
  ASSERT_EQ(list.code, 0) << list.output;
  EXPECT_EQ(lines(list.output).size(), 8u) << list.output;
  EXPECT_EQ(countOf(list.output, "integrator=nearfield"), 2u) << list.output;
  EXPECT_EQ(countOf(list.output, "integrator=ao"), 2u) << list.output;
  EXPECT_EQ(countOf(list.output, "'--seed' '2'"), 2u) << list.output;
  // The convergence curves (the next seed) run on the methods' device: reference_gl for these GL methods.
  EXPECT_EQ(countOf(list.output, "'--method' 'reference_gl'"), 2u) << list.output;
  for (auto& f : std::filesystem::recursive_directory_iterator(dir))
    EXPECT_TRUE(f.is_directory()) << "--print-commands wrote " << f.path();

  // Nothing has rendered: every render is pending, in the same order.
  CliRun pending = vgi("sweep " + kSmoke + " -o " + dir + " --pending");
  ASSERT_EQ(pending.code, 0) << pending.output;
  EXPECT_EQ(lines(pending.output), lines(list.output));

  CliRun run = vgi("sweep " + kSmoke + " -o " + dir);
  ASSERT_EQ(run.code, 0) << run.output;
  EXPECT_NE(run.output.find("[8/8]"), std::string::npos) << run.output;
  CliRun none = vgi("sweep " + kSmoke + " -o " + dir + " --pending");
  ASSERT_EQ(none.code, 0) << none.output;
  EXPECT_TRUE(lines(none.output).empty()) << none.output;
  const std::vector<std::string> csv = lines(std::string(
      std::istreambuf_iterator<char>(*std::make_unique<std::ifstream>(dir + "/results.csv")), {}));
  ASSERT_EQ(csv.size(), 1u + 2u * 3u + 4u * 4u)
      << "header + 2 counterpart curves x (1, 4, 16 spp) + 4 points x (checkpoints 1, 2, 4 and 8 spp)";
  EXPECT_EQ(csv[0].rfind("scene,method,label,role,point,seed,rays,voxels,spp,time_ms", 0), 0u) << csv[0];
  EXPECT_NE(csv[0].find("image_relmse,image_relmse_relative,image_rel_mae,image_ssim"), std::string::npos);
  EXPECT_NE(csv[0].find("indirect_rel_mae"), std::string::npos) << csv[0];
  EXPECT_NE(csv[0].find("image_equal_error_time_ratio"), std::string::npos) << csv[0];
  const nlohmann::json results = nlohmann::json::parse(std::ifstream(dir + "/results.json"));
  nlohmann::json rows = nlohmann::json::array(), curves = nlohmann::json::array();
  for (auto& r : results["rows"]) (r["role"] == "counterpart" ? curves : rows).push_back(r);
  ASSERT_EQ(rows.size(), 16u);
  ASSERT_EQ(curves.size(), 6u);
  // The counterparts' own curves converge to their references (the same integral, another seed), and
  // every point row has its equal-error time: the counterpart's time to the point's relMSE.
  std::map<std::string, std::map<int, nlohmann::json>> byCurve;
  for (auto& r : curves) byCurve[r["point"]][r["spp"].get<int>()] = r;
  ASSERT_EQ(byCurve.size(), 2u);
  for (auto& [curve, bySpp] : byCurve)
    EXPECT_LT(bySpp[16]["image"]["relmse_relative"].get<double>(),
              bySpp[1]["image"]["relmse_relative"].get<double>() / 4)
        << curve;
  for (auto& r : rows) {
    ASSERT_TRUE(r["image"].contains("equal_error_time_ratio")) << r.dump();
    EXPECT_GT(r["image"]["equal_error_time_ms"].get<double>(), 0.0);
    EXPECT_NEAR(r["image"]["equal_error_time_ratio"].get<double>(),
                r["image"]["equal_error_time_ms"].get<double>() / r["time_ms"].get<double>(), 1e-9);
  }
  // Each point's error falls from 1 to 8 samples (both methods are consistent estimators of their limit,
  // whose noise dominates at 32² and few samples); time grows with the samples.
  std::map<std::string, std::map<int, nlohmann::json>> byPoint;
  for (auto& r : rows) byPoint[r["point"]][r["spp"].get<int>()] = r;
  ASSERT_EQ(byPoint.size(), 4u);
  for (auto& [point, bySpp] : byPoint) {
    EXPECT_LT(bySpp[8]["image"]["rel_mae"].get<double>(), bySpp[1]["image"]["rel_mae"].get<double>())
        << point;
    EXPECT_GT(bySpp[8]["sample_ms"].get<double>(), bySpp[1]["sample_ms"].get<double>()) << point;
    EXPECT_FALSE(bySpp[8]["gl_renderer"].get<std::string>().empty());
  }
  // nearfield writes the indirect channel, voxel_ao does not.
  for (auto& r : rows) EXPECT_EQ(r.contains("indirect"), r["method"] == "nearfield") << r.dump();

  // The plots, tables and report; the report opened in headless chromium: every image and plot
  // loads, and its first A/B slider moves its image (the page's own load check, sweep_report.py).
  for (const char* f :
       {"convergence_builtin_cornell.png", "convergence_builtin_cornell.pdf", "passes_builtin_cornell.png",
        "passes_builtin_cornell.pdf", "pareto.md", "pareto.tex", "report.html"})
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + f)) << f;
  EXPECT_NE(
      std::string(std::istreambuf_iterator<char>(*std::make_unique<std::ifstream>(dir + "/pareto.tex")), {})
          .find("\\toprule"),
      std::string::npos);
  if (std::filesystem::exists("/usr/bin/chromium")) {
    const std::string browser =
        "timeout 120 /usr/bin/chromium --headless --no-sandbox --disable-gpu --hide-scrollbars "
        "--virtual-time-budget=5000 ";
    CliRun dom = {0, ""};
    {
      FILE* p = popen((browser + "--dump-dom file://" + dir + "/report.html 2>/dev/null").c_str(), "r");
      char buf[4096];
      for (size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) dom.output.append(buf, n);
      dom.code = pclose(p);
    }
    EXPECT_NE(dom.output.find("data-broken=\"0\""), std::string::npos) << dom.output.substr(0, 2000);
    EXPECT_NE(dom.output.find("data-slider=\"moved\""), std::string::npos) << dom.output.substr(0, 2000);
    EXPECT_EQ(dom.output.find("data-images=\"0\""), std::string::npos);
    const std::string shot = dir + "/report_screenshot.png";
    EXPECT_EQ(std::system((browser + "--window-size=1200,2400 --screenshot=" + shot + " file://" + dir +
                           "/report.html > /dev/null 2>&1")
                              .c_str()),
              0);
    EXPECT_GT(std::filesystem::file_size(shot), 10000u) << "the screenshot of the report";
  } else {
    ADD_FAILURE() << "/usr/bin/chromium is missing: scripts/setup.sh installs it";
  }

  // A second run renders nothing; collecting alone gives the same rows.
  const std::string point = dir + "/points/" + rows[0]["point"].get<std::string>();
  const auto stamp = std::filesystem::last_write_time(point + "/render.json");
  CliRun again = vgi("sweep " + kSmoke + " -o " + dir);
  ASSERT_EQ(again.code, 0) << again.output;
  EXPECT_EQ(again.output.find("[1/"), std::string::npos) << again.output;
  EXPECT_EQ(std::filesystem::last_write_time(point + "/render.json"), stamp);
  CliRun collect = vgi("sweep " + kSmoke + " -o " + dir + " --collect");
  ASSERT_EQ(collect.code, 0) << collect.output;
  EXPECT_NE(collect.output.find("22 rows"), std::string::npos) << collect.output;

  // A killed point (its final JSON never written) is rendered again, alone; meanwhile only the
  // checkpoints it finished are collected.
  std::filesystem::remove(point + "/render.json");
  CliRun partial = vgi("sweep " + kSmoke + " -o " + dir + " --collect");
  ASSERT_EQ(partial.code, 0) << partial.output;
  EXPECT_NE(partial.output.find("21 rows"), std::string::npos) << "its checkpoints stay: " << partial.output;
  CliRun killed = vgi("sweep " + kSmoke + " -o " + dir + " --pending");
  ASSERT_EQ(killed.code, 0) << killed.output;
  ASSERT_EQ(lines(killed.output).size(), 1u) << killed.output;
  EXPECT_NE(killed.output.find(point + "/render.exr"), std::string::npos) << killed.output;
  CliRun resume = vgi("sweep " + kSmoke + " -o " + dir);
  ASSERT_EQ(resume.code, 0) << resume.output;
  EXPECT_NE(resume.output.find("[1/1]"), std::string::npos) << resume.output;
  EXPECT_NE(resume.output.find("22 rows"), std::string::npos) << resume.output;
}

// A method's own reference: another method's counterpart is the same render (shared, rendered once),
// and the method's own spp replaces the experiment's.
TEST(Sweep, AMethodCanShareAnotherMethodsCounterpart) {
  const std::string file = tmp("sweep_share.json"), dir = tmp("sweep_share");
  std::filesystem::remove_all(dir);
  std::ofstream(file) << R"({"scenes": ["builtin:cornell"], "size": "16x16", "spp": 4,
    "reference": {"spp": 8},
    "methods": [{"method": "nearfield"},
                {"method": "reference", "spp": 8, "set": {"integrator": "nearfield", "visibility": "voxels"},
                 "reference": {"counterpart_of": "nearfield"}}]})";
  CliRun list = vgi("sweep " + file + " -o " + dir + " --print-commands");
  ASSERT_EQ(list.code, 0) << list.output;
  EXPECT_EQ(lines(list.output).size(), 3u) << "one shared reference, two points: " << list.output;
  EXPECT_EQ(countOf(list.output, "/references/"), 1u) << list.output;
  EXPECT_EQ(countOf(list.output, "'--spp' '8'"), 2u) << "the reference and the second point: " << list.output;
}

// "seeds": each point renders with N seeds (seed + 3k), a row each against the one reference;
// "split": each point's full reference (seed + 2) too, and each row's channels carry the total
// error (the point against it) and the model's (the model-matched reference against it); the
// report gets its seeds table and the points' FLIP maps.
TEST(Sweep, SeedsGiveARowEachAndSplitAddsTheFullReference) {
  const std::string file = tmp("sweep_seeds.json"), dir = tmp("sweep_seeds");
  std::filesystem::remove_all(dir);
  std::ofstream(file) << R"({"scenes": ["builtin:cornell"], "size": "16x16", "spp": 2, "seed": 5, "seeds": 3,
    "aovs": ["indirect"], "reference": {"spp": 8, "split": true}, "methods": [{"method": "nearfield"}]})";
  CliRun list = vgi("sweep " + file + " -o " + dir + " --print-commands");
  ASSERT_EQ(list.code, 0) << list.output;
  EXPECT_EQ(lines(list.output).size(), 5u)
      << "the reference, the full reference, three seeds: " << list.output;
  EXPECT_EQ(countOf(list.output, "/references/"), 2u) << list.output;
  for (const char* seed : {"'--seed' '8'", "'--seed' '11'", "'--seed' '7'"})  // two points; the full one
    EXPECT_EQ(countOf(list.output, seed), 1u) << seed << " in " << list.output;
  CliRun run = vgi("sweep " + file + " -o " + dir);
  ASSERT_EQ(run.code, 0) << run.output;
  const nlohmann::json res = nlohmann::json::parse(std::ifstream(dir + "/results.json"));
  EXPECT_EQ(res["seeds"], 3);
  EXPECT_EQ(res["split"], true);
  std::set<int> seeds;
  for (auto& r : res["rows"]) {
    seeds.insert(r["seed"].get<int>());
    for (const char* ch : {"image", "indirect"})
      for (const char* k : {"total_relmse", "model_relmse", "total_energy", "model_energy", "relmse_trimmed"})
        EXPECT_TRUE(r[ch].contains(k)) << ch << " " << k;
    // The model's error is the reference's against the full one: the same in every row.
    EXPECT_EQ(r["indirect"]["model_relmse"], res["rows"][0]["indirect"]["model_relmse"]);
    // nearfield's model leaves out the far field and further bounces: its indirect light is darker.
    EXPECT_LT(r["indirect"]["model_energy"].get<double>(), 0.99);
  }
  EXPECT_EQ(seeds, (std::set<int>{5, 8, 11}));
  const std::vector<std::string> csv = lines(std::string(
      std::istreambuf_iterator<char>(*std::make_unique<std::ifstream>(dir + "/results.csv")), {}));
  EXPECT_NE(csv[0].find("image_total_relmse"), std::string::npos) << csv[0];
  EXPECT_NE(csv[0].find("indirect_model_energy"), std::string::npos) << csv[0];
  if (std::filesystem::exists(dir + "/report.html")) {  // (python3-matplotlib present)
    EXPECT_TRUE(std::filesystem::exists(dir + "/seeds.md"));
  }
  size_t flipMaps = 0;
  for (auto& f : std::filesystem::recursive_directory_iterator(dir + "/points"))
    flipMaps += f.path().filename() == "flip.png";
  EXPECT_EQ(flipMaps, 3u);
  std::ofstream(tmp("sweep_split_bad.json")) << R"({"scenes": ["builtin:cornell"], "size": "16x16", "spp": 2,
    "reference": {"split": "yes"}, "methods": [{"method": "nearfield"}]})";
  CliRun bad = vgi("sweep " + tmp("sweep_split_bad.json") + " -o " + dir);
  EXPECT_EQ(bad.code, 2) << bad.output;
  EXPECT_NE(bad.output.find("reference.split"), std::string::npos) << bad.output;
}

// An error split by stage: a point's reference is the point itself with some parameters changed
// ("variant"), so it follows the point's grid values; the variant's keys replace the point's.
TEST(Sweep, AVariantReferenceIsThePointWithThoseParametersChanged) {
  const std::string file = tmp("sweep_variant.json"), dir = tmp("sweep_variant");
  std::filesystem::remove_all(dir);
  std::ofstream(file) << R"({"scenes": ["builtin:cornell"], "size": "16x16", "spp": 2,
    "reference": {"spp": 8},
    "methods": [{"method": "vpl", "set": {"bounces": 1, "clamp": 0.5}, "grid": {"vpls": [64, 256]},
                 "reference": {"variant": {"visibility": "exact", "clamp": 0}}}]})";
  CliRun list = vgi("sweep " + file + " -o " + dir + " --print-commands");
  ASSERT_EQ(list.code, 0) << list.output;
  EXPECT_EQ(lines(list.output).size(), 4u) << "two points, a reference each: " << list.output;
  for (const char* n : {"64", "256"}) {
    const std::string ref = "'--method' 'vpl' '--set' 'bounces=1' '--set' 'vpls=" + std::string(n) +
                            "' '--set' 'clamp=0' '--set' 'visibility=exact' '--size' '16x16' '--spp' '8'";
    EXPECT_EQ(countOf(list.output, ref), 1u) << ref << " in " << list.output;
  }
  EXPECT_EQ(countOf(list.output, "clamp=0.5"), 2u) << "only the points keep their clamp: " << list.output;
  std::ofstream(tmp("sweep_variant_bad.json"))
      << R"({"scenes": ["builtin:cornell"], "size": "16x16", "spp": 2,
    "methods": [{"method": "vpl", "reference": {"variant": {"visibility": "exact"}, "method": "reference"}}]})";
  CliRun bad = vgi("sweep " + tmp("sweep_variant_bad.json") + " -o " + dir);
  EXPECT_EQ(bad.code, 2) << bad.output;
  EXPECT_NE(bad.output.find("needs one of"), std::string::npos) << bad.output;
}

// The convergence curves, what the equal-error time is read off, run on the device of the method
// whose points they serve (reference_gl for a GL method, reference for a CPU one, each once while
// the two share the reference image), or with "device": "cpu" on the CPU for all.
TEST(Sweep, ConvergenceCurvesRunOnEachMethodsDevice) {
  const std::string dir = tmp("sweep_device");
  for (const char* device : {"same", "cpu"}) {
    const std::string file = tmp(std::string("sweep_device_") + device + ".json");
    std::ofstream(file) << R"({"scenes": ["builtin:cornell"], "size": "16x16", "spp": 2,
      "reference": {"spp": 8, "convergence": [1, 4], "device": ")"
                        << device << R"("},
      "methods": [{"method": "voxel_ao"},
                  {"method": "reference", "set": {"integrator": "ao", "radius": 0.0960740447},
                   "reference": {"counterpart_of": "voxel_ao"}}]})";
    CliRun list = vgi("sweep " + file + " -o " + dir + " --print-commands");
    ASSERT_EQ(list.code, 0) << list.output;
    EXPECT_EQ(countOf(list.output, "/references/"), 1u) << list.output;
    EXPECT_EQ(countOf(list.output, "/curves/reference_gl-"), std::string(device) == "same" ? 1u : 0u)
        << list.output;
    EXPECT_EQ(countOf(list.output, "/curves/reference-"), 1u) << list.output;
  }
  CliRun bad = vgi("sweep " + tmp("sweep_device_bad.json") + " -o " + dir);
  std::ofstream(tmp("sweep_device_bad.json")) << R"({"scenes": ["builtin:cornell"], "size": "16x16",
    "spp": 2, "reference": {"device": "gpu"}, "methods": [{"method": "voxel_ao"}]})";
  bad = vgi("sweep " + tmp("sweep_device_bad.json") + " -o " + dir);
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.output.find("reference.device"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("gpu"), std::string::npos) << bad.output;
}

// Every shipped experiment file loads and expands (the scenes it needs from ../shared/scenes, where
// those are present): an experiment file that rots is found here, not by its next user.
TEST(Sweep, EveryShippedExperimentFileLoads) {
  const std::string dir = std::string(VGI_TEST_DATA) + "/../../scenes/experiments";
  int files = 0;
  for (auto& f : std::filesystem::directory_iterator(dir)) {
    if (f.path().extension() != ".json") continue;
    const std::string text(std::istreambuf_iterator<char>(*std::make_unique<std::ifstream>(f.path())), {});
    // An experiment on a shared scene that is absent here (a fresh clone without ../shared) is skipped.
    bool absent = false;
    for (const auto& [name, file] : {std::pair<const char*, const char*>{"sibenik", "sibenik/sibenik.obj"},
                                     {"bunny", "stanford-bunny/bun_zipper.ply"},
                                     {"dragon", "stanford-dragon/dragon_vrip_res2.ply"}})
      absent = absent || (text.find(name) != std::string::npos && test::sharedScene(file).empty());
    if (absent) continue;
    ++files;
    // Relative scene paths are the repository root's, as the README runs them.
    const auto cwd = std::filesystem::current_path();
    std::filesystem::current_path(std::string(VGI_TEST_DATA) + "/../..");
    CliRun list = vgi("sweep " + f.path().string() + " -o " + tmp("shipped_" + f.path().stem().string()) +
                      " --print-commands");
    std::filesystem::current_path(cwd);
    EXPECT_EQ(list.code, 0) << f.path() << ": " << list.output;
    EXPECT_GT(lines(list.output).size(), 1u) << f.path();
  }
  EXPECT_GE(files, 3);
}

// The equal-error time against hand-computed curves: log-log interpolation inside, Monte Carlo's
// 1/samples rate on the per-sample time outside.
TEST(Sweep, EqualErrorTimeInterpolatesAndExtrapolates) {
  // relMSE = 1 / samples, 10 ms set-up, 2 ms per sample.
  std::vector<CurvePoint> curve;
  for (int n : {1, 4, 16, 64}) curve.push_back({10.0 + 2.0 * n, 2.0 * n, 1.0 / n});
  EqualError inside = equalErrorTime(curve, 1.0 / 4);
  ASSERT_TRUE(inside.valid);
  EXPECT_FALSE(inside.extrapolated);
  EXPECT_NEAR(inside.timeMs, 18.0, 1e-9);  // a measured point
  EqualError between = equalErrorTime(curve, 0.5);
  EXPECT_NEAR(between.timeMs, std::sqrt(12.0 * 18.0), 1e-9);  // halfway in log error: geometric mean
  EqualError below = equalErrorTime(curve, 1.0 / 256);        // better than the curve's end
  ASSERT_TRUE(below.valid);
  EXPECT_TRUE(below.extrapolated);
  EXPECT_NEAR(below.timeMs, 10.0 + 2.0 * 256, 1e-9);
  EqualError above = equalErrorTime(curve, 2.0);  // worse than one sample: half a sample's time
  EXPECT_TRUE(above.extrapolated);
  EXPECT_NEAR(above.timeMs, 10.0 + 1.0, 1e-9);
  EXPECT_FALSE(equalErrorTime({}, 0.1).valid);
  EXPECT_FALSE(equalErrorTime(curve, 0.0).valid);
  EXPECT_FALSE(equalErrorTime(curve, std::nan("")).valid);
}

// A time budget: every point stops after its wall time (`vgi render --time-limit`), with fewer samples
// than the most it may take, is done (not re-rendered) and is collected at the samples it reached.
TEST(Sweep, TimeBudgetStopsEachPoint) {
  const std::string dir = tmp("sweep_budget"), file = tmp("sweep_budget.json");
  std::filesystem::remove_all(dir);
  std::ofstream(file) << R"({"scenes": ["builtin:cornell"], "size": "16x16", "spp": 1000000,
    "time_budget_s": 0.5, "reference": {"method": "reference", "set": {"integrator": "direct"}, "spp": 4},
    "methods": [{"method": "reference", "set": {"integrator": "direct"}}]})";
  CliRun run = vgi("sweep " + file + " -o " + dir);
  ASSERT_EQ(run.code, 0) << run.output;
  const nlohmann::json rows = nlohmann::json::parse(std::ifstream(dir + "/results.json"))["rows"];
  ASSERT_EQ(rows.size(), 1u) << rows.dump();
  EXPECT_TRUE(rows[0]["time_limited"].get<bool>());
  EXPECT_GE(rows[0]["spp"].get<int>(), 1);
  EXPECT_LT(rows[0]["spp"].get<int>(), 1000000);
  EXPECT_GE(rows[0]["time_ms"].get<double>(), 100.0);
  CliRun again = vgi("sweep " + file + " -o " + dir);
  ASSERT_EQ(again.code, 0) << again.output;
  EXPECT_EQ(again.output.find("[1/"), std::string::npos) << "a time-limited render is done: " << again.output;

  // The render option itself: bad values are refused naming it.
  for (const char* bad : {"-1", "nan", "inf"}) {
    CliRun r = vgi(std::string("render --method direct --size 8x8 --quiet --time-limit ") + bad + " -o " +
                   tmp("tl.exr"));
    EXPECT_EQ(r.code, 2) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("--time-limit"), std::string::npos) << r.output;
  }
}

TEST(Sweep, BadExperimentFilesAreRefusedBeforeAnythingRenders) {
  const std::string dir = tmp("sweep_bad");
  auto refused = [&](const std::string& name, const std::string& json,
                     std::initializer_list<std::string> needles, const std::string& out = "") {
    const std::string file = tmp(name + ".json");
    std::ofstream(file) << json;
    std::filesystem::remove_all(dir);
    CliRun r = vgi("sweep " + file + " -o " + (out.empty() ? dir : out));
    EXPECT_EQ(r.code, 2) << name << ": " << r.output;
    for (auto& n : needles)
      EXPECT_NE(r.output.find(n), std::string::npos) << name << ": '" << n << "' in " << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir + "/points")) << name << " rendered";
  };
  const std::string head = R"({"scenes": ["builtin:cornell"], "size": "16x16", "spp": 2, )";
  refused("unknown_method", head + R"("methods": [{"method": "nearfeld"}]})", {"nearfeld", "methods[0]"});
  refused("unknown_param", head + R"("methods": [{"method": "nearfield", "grid": {"rayz": [4]}}]})",
          {"rayz"});
  refused("empty_grid", head + R"("methods": [{"method": "nearfield", "grid": {"rays": []}}]})",
          {"grid.rays", "[]"});
  refused("out_of_range", head + R"("methods": [{"method": "nearfield", "grid": {"rays": [4, 0]}}]})",
          {"rays", "0"});
  refused("unknown_key", head + R"("methods": [{"method": "nearfield"}], "sceens": []})", {"sceens"});
  refused("no_methods", head + R"("methods": []})", {"methods"});
  refused("bad_size",
          R"({"scenes": ["builtin:cornell"], "size": "16y16", "spp": 2, "methods": [{"method": "direct"}]})",
          {"16y16"});
  refused("bad_spp",
          R"({"scenes": ["builtin:cornell"], "size": "16x16", "spp": 0, "methods": [{"method": "direct"}]})",
          {"spp", "0"});
  refused("bad_budget", head + R"("time_budget_s": -1, "methods": [{"method": "direct"}]})",
          {"time_budget_s", "-1"});
  refused("empty_convergence",
          head + R"("reference": {"convergence": []}, "methods": [{"method": "nearfield"}]})",
          {"reference.convergence", "[]"});
  refused("convergence_beyond_spp",
          head + R"("reference": {"spp": 8, "convergence": [4, 9]}, "methods": [{"method": "nearfield"}]})",
          {"reference.convergence", "9"});
  refused(
      "method_reference_both",
      head +
          R"("methods": [{"method": "nearfield", "reference": {"method": "reference", "counterpart_of": "direct"}}]})",
      {"methods[0].reference"});
  refused("method_reference_unknown",
          head + R"("methods": [{"method": "reference", "reference": {"counterpart_of": "nearfeld"}}]})",
          {"nearfeld", "counterpart_of"});
  // A reference image of another size.
  const std::string ref = tmp("sweep_ref_8x8.exr");
  ASSERT_EQ(vgi("render --method direct --size 8x8 --spp 1 --quiet -o " + ref).code, 0);
  refused("ref_size", head + R"("reference": {"file": ")" + ref + R"("}, "methods": [{"method": "direct"}]})",
          {ref, "8x8", "16x16"});
  refused("ref_missing",
          head + R"("reference": {"file": "/nonexistent/r.exr"}, "methods": [{"method": "direct"}]})",
          {"/nonexistent/r.exr"});
  refused("unwritable", head + R"("methods": [{"method": "direct"}]})",
          {"/proc/vgi_sweep", "cannot be written"}, "/proc/vgi_sweep");
  refused("frames_checkpoints",
          head + R"("frames": 3, "checkpoints": [1], "methods": [{"method": "direct"}]})",
          {"checkpoints", "frames"});
  refused(
      "scene_frames",
      R"({"scenes": [{"scene": "builtin:cornell", "frames": -2}], "size": "16x16", "spp": 2, "methods": [{"method": "direct"}]})",
      {"builtin:cornell", "frames", "-2"});
  refused(
      "scene_twice",
      R"({"scenes": ["builtin:cornell", {"scene": "builtin:cornell"}], "size": "16x16", "spp": 2, "methods": [{"method": "direct"}]})",
      {"builtin:cornell", "twice"});
  refused("frames_convergence",
          head + R"("frames": 3, "reference": {"convergence": [1]}, "methods": [{"method": "nearfield"}]})",
          {"frames", "reference.convergence"});
  refused("bad_frames", head + R"("frames": 0, "methods": [{"method": "direct"}]})", {"frames", "0"});
  refused("bad_time_step", head + R"("frames": 2, "time_step": 0, "methods": [{"method": "direct"}]})",
          {"time_step", "0"});
  CliRun missing = vgi("sweep " + tmp("no_such_experiment.json") + " -o " + dir);
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.output.find("no_such_experiment.json"), std::string::npos) << missing.output;
}

}  // namespace vgi

namespace vgi {
// `vgi compare --reference FILE`: the counterpart read from an earlier comparison's exact image (its
// AOVs and stats beside it) gives the same errors as rendering it; an image of another size is refused.
TEST(Sweep, CompareAcceptsAnExistingReference) {
  const std::string a = tmp("cmpref_a.exr"), b = tmp("cmpref_b.exr");
  test::CliRun first =
      test::vgi("compare --method nearfield --spp 2 --ref-spp 16 --size 24x24 --quiet -o " + a);
  ASSERT_EQ(first.code, 0) << first.output;
  const std::string exact = tmp("cmpref_a.exact.exr");
  test::CliRun second =
      test::vgi("compare --method nearfield --spp 2 --size 24x24 --quiet --reference " + exact + " -o " + b);
  ASSERT_EQ(second.code, 0) << second.output;
  const nlohmann::json ja = nlohmann::json::parse(std::ifstream(tmp("cmpref_a.json")));
  const nlohmann::json jb = nlohmann::json::parse(std::ifstream(tmp("cmpref_b.json")));
  for (const char* ch : {"image", "indirect", "direct"})
    EXPECT_EQ(ja["error"][ch]["relmse"], jb["error"][ch]["relmse"]) << ch;
  EXPECT_EQ(jb["exact"]["file"], exact);
  EXPECT_EQ(jb["exact"]["spp"], 16);
  test::CliRun wrong =
      test::vgi("compare --method nearfield --spp 1 --size 20x24 --quiet --reference " + exact + " -o " + b);
  EXPECT_EQ(wrong.code, 2);
  EXPECT_NE(wrong.output.find("24x24"), std::string::npos) << wrong.output;
  EXPECT_NE(wrong.output.find("20x24"), std::string::npos) << wrong.output;
}
}  // namespace vgi

namespace vgi {
// An animation experiment ("frames"): one row per point, the frames' mean static metrics and the
// temporal ones, per-frame error maps. Known answers: the exact method against itself (same
// integrator, samples and seed: the same images) has zero error and zero temporal error, with the
// same change as its reference; a GL method's change is measured, and the moving triangle changes
// the exact images from frame to frame.
TEST(Sweep, AnimationExperimentsMeasureTheTemporalError) {
  const std::string dir = tmp("sweep_frames"), file = tmp("sweep_frames.json");
  std::filesystem::remove_all(dir);
  const std::string scene = test::writeMovingTriangleScene("sweep_frames_scene");
  std::ofstream(file) << R"({"scenes": [{"scene": ")" << scene
                      << R"(", "frames": 3, "time_step": 0.5}], "size": "24x24", "spp": 2,
    "reference": {"method": "reference", "set": {"integrator": "direct"}, "spp": 2},
    "methods": [{"method": "reference", "set": {"integrator": "direct"}}, {"method": "direct"},
                {"method": "reference", "label": "floor", "seed": 2, "set": {"integrator": "direct"}}]})";
  CliRun run = vgi("sweep " + file + " -o " + dir);
  ASSERT_EQ(run.code, 0) << run.output;
  const nlohmann::json res = nlohmann::json::parse(std::ifstream(dir + "/results.json"));
  EXPECT_EQ(res["animations"][scene]["frames"].get<int>(), 3);
  const nlohmann::json& rows = res["rows"];
  ASSERT_EQ(rows.size(), 3u) << rows.dump();
  for (auto& r : rows) {
    EXPECT_EQ(r["frames"].get<int>(), 3);
    ASSERT_TRUE(r.contains("image") && r["image"].contains("temporal_error")) << r.dump();
    EXPECT_GT(r["image"]["change_reference"].get<double>(), 0.01) << "the triangle moves";
    for (int t = 0; t < 3; ++t)
      EXPECT_TRUE(std::filesystem::exists(dir + "/points/" + r["point"].get<std::string>() + "/error_000" +
                                          std::to_string(t) + ".png"));
  }
  std::map<std::string, nlohmann::json> byLabel;
  for (auto& r : rows) byLabel[r["label"].get<std::string>()] = r;
  const nlohmann::json &same = byLabel["reference"], &gl = byLabel["direct"], &floor = byLabel["floor"];
  // The exact method with another seed: the reference's own noise, the floor of the temporal error.
  EXPECT_GT(floor["image"]["rel_mae"].get<double>(), 0.0);
  EXPECT_GT(floor["image"]["temporal_error"].get<double>(), 0.0);
  EXPECT_EQ(same["image"]["temporal_error"].get<double>(), 0.0);
  EXPECT_EQ(same["image"]["rel_mae"].get<double>(), 0.0);
  EXPECT_EQ(same["image"]["change"].get<double>(), same["image"]["change_reference"].get<double>());
  EXPECT_GT(gl["image"]["change"].get<double>(), 0.01);
  EXPECT_TRUE(std::isfinite(gl["image"]["temporal_error"].get<double>()));
  const std::string csv(
      std::istreambuf_iterator<char>(*std::make_unique<std::ifstream>(dir + "/results.csv")), {});
  EXPECT_NE(csv.find("image_temporal_error"), std::string::npos) << csv;
  if (std::filesystem::exists(dir + "/report.html")) {  // (python3-matplotlib present)
    const std::string report(
        std::istreambuf_iterator<char>(*std::make_unique<std::ifstream>(dir + "/report.html")), {});
    EXPECT_NE(report.find("class='strip'"), std::string::npos);
    EXPECT_NE(report.find("error_0002.png"), std::string::npos);
  }
  // Done renders are not run again.
  CliRun again = vgi("sweep " + file + " -o " + dir);
  ASSERT_EQ(again.code, 0) << again.output;
  EXPECT_EQ(again.output.find("[1/"), std::string::npos) << again.output;
}
}  // namespace vgi
