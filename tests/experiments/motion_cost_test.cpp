// The cost of motion (experiments/motion_cost.h): two animations' per-pass timings, frame 0 left out.
#include "experiments/motion_cost.h"

#include <fstream>
#include <nlohmann/json.hpp>

#include "apps/cli_util.h"

namespace vgi {
using test::CliRun;
using test::tmp;
using test::vgi;

namespace {
// The stats of an animation whose frames after the first take `passes` (ms); frame 0 takes 1000 each.
nlohmann::json animation(const nlohmann::json& passes, int frames, const std::string& method = "vct") {
  nlohmann::json f = nlohmann::json::array();
  nlohmann::json first = passes;
  for (auto& [k, v] : first.items()) v = 1000.0;
  f.push_back({{"timings_ms", first}});
  for (int i = 1; i < frames; ++i) f.push_back({{"timings_ms", passes}});
  return {{"method", method}, {"width", 64}, {"height", 64}, {"frames", f}};
}
}  // namespace

TEST(MotionCost, ADoubledFrameDoublesTheCost) {
  const nlohmann::json still = animation({{"shade", 2.0}, {"voxelize", 1.0}}, 4);
  const MotionCost same = motionCost(still, still);
  EXPECT_EQ(same.frames, 3);
  EXPECT_EQ(same.ratio(), 1.0);  // frame 0's set-up is left out of both
  const MotionCost doubled = motionCost(animation({{"shade", 4.0}, {"voxelize", 2.0}}, 4), still);
  EXPECT_EQ(doubled.ratio(), 2.0);
  EXPECT_EQ(doubled.passes.at("voxelize").movingMs, 2.0);
  EXPECT_EQ(doubled.passes.at("voxelize").stillMs, 1.0);
  // A pass only the moving run has (re-voxelizing the object) counts against 0.
  const MotionCost extra =
      motionCost(animation({{"shade", 2.0}, {"voxelize", 1.0}, {"dynamic", 3.0}}, 4), still);
  EXPECT_EQ(extra.passes.at("dynamic").stillMs, 0.0);
  EXPECT_EQ(extra.ratio(), 2.0);
  EXPECT_EQ(extra.toJson()["passes"]["dynamic"]["ratio"], "undefined");  // not null
  // Times are milliseconds in [0, 1e12]: a negative one (a ratio of −25) or one whose sums overflow
  // (1.7e308: moving_ms null) is refused naming the file, the frame and the pass.
  for (double bad : {-5.0, 1.7e308, 1e13})
    test::expectError(
        [&] {
          motionCost(animation({{"shade", bad}}, 3), still, "m.json", "s.json");
        },
        {"m.json", "frame 1", "timings_ms.shade", "not a time in milliseconds"});
  test::expectError(
      [&] {
        motionCost(animation({{"a", 1.0}}, 1), still, "m.json", "s.json");
      },
      {"m.json", "at least 2 frames"});
  test::expectError(
      [&] {
        motionCost(animation({{"a", 1.0}}, 4, "nearfield"), still, "m.json", "s.json");
      },
      {"'method'", "nearfield"});
  test::expectError([&] { motionCost(animation({{"a", 1.0}}, 3), still, "m.json", "s.json"); }, {"3 frames"});
}

TEST(MotionCost, BenchMotionReadsTwoStatsFiles) {
  std::ofstream(tmp("still.json")) << animation({{"shade", 2.0}}, 3).dump();
  std::ofstream(tmp("moving.json")) << animation({{"shade", 6.0}}, 3).dump();
  CliRun r = vgi("bench motion --json " + tmp("moving.json") + " " + tmp("still.json"));
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(nlohmann::json::parse(r.output)["ratio"], 3.0);
  CliRun t = vgi("bench motion " + tmp("moving.json") + " " + tmp("still.json"));
  EXPECT_NE(t.output.find("all passes"), std::string::npos) << t.output;
  CliRun bad = vgi("bench motion " + tmp("nothing.json") + " " + tmp("still.json"));
  EXPECT_EQ(bad.code, 2) << bad.output;
  EXPECT_NE(bad.output.find("nothing.json"), std::string::npos) << bad.output;
}

}  // namespace vgi
