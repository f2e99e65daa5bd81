// One render as `vgi render` runs it: load the scene, resolve parameters
// (scene preset, then --set), create the method, make a GL context if the
// method needs one, render, and describe everything in a stats JSON.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/gl_context.h"
#include "illum/method.h"

namespace vgi {

struct RenderOptions {
  std::string scene = "builtin:cornell";
  std::string method = "direct";
  std::vector<std::string> set;  // key=value
  std::string preset;            // scene preset name, applied before `set`
  int width = 512, height = 512;
  int spp = 16;
  uint32_t seed = 1;
  int threads = 0;
  float time = 0;
  GlBackend gl = GlBackend::Auto;
  bool progress = true;
  std::vector<std::string> aovs;  // --aov: extra output channels
};

struct RenderOutput {
  RenderResult result;
  nlohmann::json stats;
};

// Parses "WxH" (each 1..16384); throws naming the option and value.
void parseSize(const std::string& text, int& width, int& height);

RenderOutput runRender(const RenderOptions& options);

// Writes <stem>.exr, <stem>.png and <stem>.json (stats) for output path `path`
// (.exr or .png), and <stem>.<aov>.exr/.png per extra output; returns the files written.
std::vector<std::string> writeRenderOutputs(const RenderOutput& out, const std::string& path, float exposure);

// Throws if `path` cannot be written (missing folder, bad extension) — checked
// before a long render, so nothing is lost at the end.
void checkOutputPath(const std::string& path);
// Throws if the folder `path` would be written into does not exist (`option` names it).
void checkOutputFolder(const std::string& path, const std::string& option);

// The parameter table of a method, for --help-module.
std::string describeMethod(const std::string& name);

}  // namespace vgi
