// --script files of vgi view: a JSON list of {"kind": value} events, each
// checked (kind, type, range, output paths) before anything runs.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace vgi::app {

// One event of a --script file.
struct ScriptEvent {
  nlohmann::json value;
  std::string kind;
  size_t index = 0;
};

// The events of the file at `path`; throws vgi::Error naming the file, the event and the value.
std::vector<ScriptEvent> loadScript(const std::string& path);

// A JSON scalar as --set text (the script checked the values are scalars).
std::string setText(const nlohmann::json& v);

}  // namespace vgi::app
