// A render's options and their one serialization: the `vgi render` arguments
// and the job JSON (`vgi render --job F.json`; "job" in every render's stats).
// The flags are spelled once, here: the sweep's commands and the viewer's
// screenshot command are built by renderArgs, and tests/apps/cli_test.cpp
// parses renderArgs through the real command line (`vgi render --print-job`)
// and checks it gives back the same job.
#pragma once
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/gl_context.h"
#include "core/scene.h"
#include "illum/framework/method.h"

namespace vgi {

struct RenderOptions {
  std::string scene = "builtin:cornell";
  std::string method = defaultMethodName();
  bool methodGiven = false;      // --method was on the command line (a preset may name its method otherwise)
  std::vector<std::string> set;  // key=value
  std::string preset;            // scene preset name, applied before `set`
  int width = 512, height = 512;
  int spp = 16;
  uint32_t seed = 1;
  int threads = 0;
  float time = 0;
  int frames = 1;  // > 1: an animation from `time`, `timeStep` apart
  float timeStep = 1.0f / 30.0f;
  GlBackend gl = GlBackend::Auto;
  bool progress = true;
  std::vector<std::string> aovs;                          // --aov: extra output channels
  Accumulation accumulation = Accumulation::Compensated;  // --accumulate
  std::vector<int> checkpoints;  // --checkpoints: sample counts to write the image at (a still)
  double timeLimitS = 0;         // --time-limit: a still stops accumulating after this wall time
  std::optional<Camera> camera;  // --camera: replaces the scene's
  // --light I=x,y,z: light I (scene order) placed at x,y,z (point and spot lights)
  std::vector<std::pair<int, glm::vec3>> lightPositions;
};

// Parses "WxH" (each 1..16384); throws naming the option and value.
void parseSize(const std::string& text, int& width, int& height);
// --camera text: "px,py,pz,tx,ty,tz,ux,uy,uz[,fov_y_deg]" (the stats JSON's camera.option);
// throws naming the value when it is not a camera.
Camera parseCamera(const std::string& text);
std::string cameraText(const Camera& camera);
// --light text: "I=x,y,z" (index, position); throws naming the value.
std::pair<int, glm::vec3> parseLightPosition(const std::string& text);
std::string lightPositionText(int index, glm::vec3 position);
// Throws naming the option when a value of `options` is out of range.
void checkRenderOptions(const RenderOptions& options);

// The `vgi render` arguments (after "render") that give `o`: the options
// that differ from RenderOptions{} (the method always), in a fixed order.
std::vector<std::string> renderArgs(const RenderOptions& o);
// The same as a command line for a shell: "vgi render --flag 'VALUE' …".
std::string renderCommandLine(const RenderOptions& o);
// `s` in single quotes for a POSIX shell.
std::string shellQuote(const std::string& s);

// The job as JSON: every option by name (the flag's name without "--": size
// as width/height, camera and lights in their --camera / --light text).
nlohmann::json renderJobJson(const RenderOptions& o);
// A job from JSON (a job file, or a render's stats JSON: its "job"); keys
// absent keep RenderOptions{}'s value. Throws vgi::Error naming `origin`, the
// key and the value for an unknown key or a value of the wrong type or range.
RenderOptions readRenderJob(const nlohmann::json& j, const std::string& origin);

}  // namespace vgi
