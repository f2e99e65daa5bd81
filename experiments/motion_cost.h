// The cost of motion (issue "What voxel-GI users complain about"): what one moving object costs per
// frame, pass by pass, against the same scene with it standing still. Both are the stats JSONs of
// `vgi render --frames N` (N >= 2) of one method at one size; frame 0 builds what both build once
// and is left out; each pass's time is its mean over the other frames ("timings_ms": GPU timers
// where measured, else CPU), and the ratio moving / still is per pass and for their sum.
#pragma once
#include <map>
#include <nlohmann/json_fwd.hpp>
#include <string>

namespace vgi {

struct MotionCost {
  int frames = 0;  // frames averaged (each run's, after frame 0)
  struct Pass {
    double stillMs = 0, movingMs = 0;
  };
  std::map<std::string, Pass> passes;  // every pass of either run (0 where a run has none)
  double stillMs = 0, movingMs = 0;    // per frame, all passes
  double ratio() const;                // movingMs / stillMs (∞ if still is 0 and moving is not)
  nlohmann::json toJson() const;
  std::string table() const;  // per pass: still, moving, ratio; then all passes (`vgi bench motion`)
};

// Throws naming the file when a stats JSON is not an animation of at least 2 frames, or the two are of
// different methods, sizes or frame counts.
MotionCost motionCost(const nlohmann::json& moving, const nlohmann::json& still,
                      const std::string& movingName = "moving", const std::string& stillName = "still");

}  // namespace vgi
