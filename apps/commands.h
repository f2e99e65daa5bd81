#pragma once
#include <CLI/CLI.hpp>
#include <sstream>
#include <string>
#include <vector>

// Declarations only: vgi_main.cpp includes this with CLI11 and nothing of the
// library's (its commands include what they use).
namespace vgi {
struct RenderOptions;
struct DiffOptions;
struct ImageDiff;
}  // namespace vgi

namespace vgi::app {
// Thrown after a Ctrl-C'd command has written what it completed: vgi exits 130.
struct Interrupted {};
// Thrown by a command that finished but failed (the viewer after a failed screenshot or GL errors).
struct ExitCode {
  int code;
};

// The options `render` and `compare` share (scene, method, set, preset, size,
// spp, seed, threads, time, gl, quiet), read into `opt` and the raw texts of
// `args`; applyRenderArgs() parses the texts (size, GL backend) into `opt`.
struct RenderArgs {
  std::string size, gl = "auto", accumulate = "compensated", camera;
  std::vector<std::string> lights;
  bool quiet = false;
};
void addRenderOptions(CLI::App* cmd, RenderOptions& opt, RenderArgs& args);
void applyRenderArgs(const RenderArgs& args, RenderOptions& opt);

// relMSE's --epsilon / --relative-epsilon (diff and compare); one line of a
// diff for a table, and the table's header.
void addDiffOptions(CLI::App* cmd, DiffOptions& options);
std::string diffLine(const ImageDiff& d);
std::string diffHeader(bool flip);  // flip: the FLIP column first

// Each adds its subcommand to the app; the callback runs it.
void addRenderCommand(CLI::App& app);
void addInfoCommand(CLI::App& app);
void addDiffCommand(CLI::App& app);
void addVoxelizeCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);
void addCompareCommand(CLI::App& app);
void addSweepCommand(CLI::App& app);
void addViewCommand(CLI::App& app);
}  // namespace vgi::app
