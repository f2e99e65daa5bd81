#pragma once
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace vgi::app {
// "a,b,,c" → {a, b, c}.
inline std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

// Each adds its subcommand to the app; the callback runs it.
void addRenderCommand(CLI::App& app);
void addInfoCommand(CLI::App& app);
void addDiffCommand(CLI::App& app);
void addVoxelizeCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);
void addCompareCommand(CLI::App& app);
}  // namespace vgi::app
