#pragma once
#include <CLI/CLI.hpp>

namespace vgi::app {
// Each adds its subcommand to the app; the callback runs it.
void addRenderCommand(CLI::App& app);
void addInfoCommand(CLI::App& app);
void addDiffCommand(CLI::App& app);
void addVoxelizeCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);
}  // namespace vgi::app
