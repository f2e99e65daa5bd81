#include "experiments/motion_cost.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/json_text.h"

namespace vgi {

namespace {
// Each pass's mean time per frame over frames 1 … N−1.
std::map<std::string, double> meanPassTimes(const nlohmann::json& stats, const std::string& name) {
  if (!stats.is_object() || !stats.contains("frames") || !stats["frames"].is_array() ||
      stats["frames"].size() < 2)
    fail(name, ": not the stats of an animation of at least 2 frames (vgi render --frames N)");
  const nlohmann::json& frames = stats["frames"];
  std::map<std::string, double> mean;
  for (size_t f = 1; f < frames.size(); ++f) {
    if (!frames[f].contains("timings_ms") || !frames[f]["timings_ms"].is_object())
      fail(name, ": frame ", f, " has no timings_ms");
    for (auto& [pass, ms] : frames[f]["timings_ms"].items()) {
      // A time a render measured: a number of milliseconds ≥ 0, and below 10¹² (30 years), so that
      // sums over passes and frames stay finite (a −5 gave a ratio of −25; 1.7e308 gave null).
      if (!ms.is_number() || !(ms.get<double>() >= 0) || !(ms.get<double>() <= 1e12))
        fail(name, ": frame ", f, " timings_ms.", pass, " = ", jsonExcerpt(ms),
             " is not a time in milliseconds (a number in [0, 1e12])");
      mean[pass] += ms.get<double>() / double(frames.size() - 1);
    }
  }
  return mean;
}
}  // namespace

double MotionCost::ratio() const {
  return stillMs > 0 ? movingMs / stillMs : (movingMs > 0 ? INFINITY : 1.0);
}

nlohmann::json MotionCost::toJson() const {
  nlohmann::json p = nlohmann::json::object();
  for (auto& [name, t] : passes)
    p[name] = {
        {"still_ms", t.stillMs},
        {"moving_ms", t.movingMs},
        {"ratio", t.stillMs > 0 ? finiteOrUndefined(t.movingMs / t.stillMs) : nlohmann::json(kUndefined)}};
  return {{"frames", frames},
          {"still_ms", stillMs},
          {"moving_ms", movingMs},
          {"ratio", finiteOrUndefined(ratio())},
          {"passes", p}};
}

MotionCost motionCost(const nlohmann::json& moving, const nlohmann::json& still,
                      const std::string& movingName, const std::string& stillName) {
  const std::map<std::string, double> m = meanPassTimes(moving, movingName),
                                      s = meanPassTimes(still, stillName);
  for (const char* key : {"method", "width", "height"})
    if (moving.value(key, nlohmann::json()) != still.value(key, nlohmann::json()))
      fail(movingName, " and ", stillName, " differ in '", key, "' (",
           moving.value(key, nlohmann::json()).dump(), " against ", still.value(key, nlohmann::json()).dump(),
           "): the cost of motion compares one method at one size");
  if (moving["frames"].size() != still["frames"].size())
    fail(movingName, " has ", moving["frames"].size(), " frames, ", stillName, " ", still["frames"].size());
  MotionCost c;
  c.frames = int(moving["frames"].size()) - 1;
  for (auto& [pass, ms] : m) c.passes[pass].movingMs = ms, c.movingMs += ms;
  for (auto& [pass, ms] : s) c.passes[pass].stillMs = ms, c.stillMs += ms;
  return c;
}

std::string MotionCost::table() const {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line,
                "%-24s %12s %12s %8s   (ms per frame, mean of %d frames after the first)\n", "pass", "still",
                "moving", "ratio", frames);
  out += line;
  for (auto& [name, t] : passes) {
    char r[32] = "-";
    if (t.stillMs > 0) std::snprintf(r, sizeof r, "%.3f", t.movingMs / t.stillMs);
    std::snprintf(line, sizeof line, "%-24s %12.3f %12.3f %8s\n", name.c_str(), t.stillMs, t.movingMs, r);
    out += line;
  }
  char all[32] = "undefined";  // still 0, moving not (as in the JSON)
  if (std::isfinite(ratio())) std::snprintf(all, sizeof all, "%.3f", ratio());
  std::snprintf(line, sizeof line, "%-24s %12.3f %12.3f %8s\n", "all passes", stillMs, movingMs, all);
  return out + line;
}

}  // namespace vgi
