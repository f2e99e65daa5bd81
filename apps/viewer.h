// `vgi view`: the interactive viewer (GLFW window, GL 4.5 core, Dear ImGui).
// Every frame it adds one sample of the method to the accumulation the
// framework's sample loop keeps (illum/framework/sample_loop.h: SampleSession) and
// shows the mean so far; moving the camera, the scene time or a parameter
// starts the accumulation again. The panel is generated from the method's
// parameter table; the per-pass GPU timings are the profiler's.
//
// Headless use (scripts, tests, recordings; under Xvfb on a machine without
// a display):
//   --frames N --screenshot FILE   N samples, FILE (+ .png/.exr and the same
//                                  stats JSON as `vgi render`), exit
//   --script FILE                  replays events (below), then exits
//   --record DIR                   writes every shown frame as DIR/frame_NNNNN.png
// A script is a JSON list of events, applied in order:
//   {"frames": N}                  show N frames (one sample each)
//   {"orbit": [yaw_deg, pitch_deg]}  about the camera's target
//   {"move": [right, up, forward]} in scene diagonals
//   {"reset_camera": true}         the scene's camera
//   {"method": "voxel_ao"}         switch the method (its defaults)
//   {"set": {"rays": 8}}           change parameters of the current method
//   {"show": "indirect"}           show an output of the method ("image": the image),
//                                  or its light maps: "rsm.radiance", "rsm.normal",
//                                  "rsm.position", "rsm.distance" (reflective shadow
//                                  maps) or "shadow_map.distance"
//   {"light_face": 2}              the light-map face shown (a point light has 6)
//   {"light": "0=0.3,0.5,0.2"}     place point/spot light 0 (as `vgi render --light`):
//                                  the light maps and radiance follow, the grid stays
//   {"time": 0.5}                  the animation time
//   {"screenshot": "shot.png"}     write the accumulation so far (+ the stats JSON)
//   {"scene": "scenes/sibenik.json"}  load another scene (the method kept)
//   {"window_screenshot": "w.png"} write the window as shown, panel included
// An event that fails (an unknown method, a value out of range) is reported
// in the panel and the log and the viewer keeps running, as typed input does.
#pragma once
#include <string>

#include "illum/run/render_job.h"

namespace vgi::app {

struct ViewOptions {
  RenderOptions render;  // scene, method, --set, size, seed; spp: the most samples accumulated
  int frames = 0;        // > 0: headless: N samples, --screenshot, exit
  std::string screenshot, script, record;
  float exposure = 1.0f;
};

// Opens the window and runs until it is closed (Esc), the frames are done or
// the script ended; returns the exit code (0, or 1 after a failed screenshot).
int runViewer(const ViewOptions& options);

}  // namespace vgi::app
