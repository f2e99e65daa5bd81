#include "apps/viewer_script.h"

#include <algorithm>

#include "core/error.h"
#include "core/json_text.h"
#include "core/output_files.h"
#include "core/params.h"
#include "illum/run/render_job.h"
#include "illum/run/render_outputs.h"

namespace vgi::app {

std::vector<ScriptEvent> loadScript(const std::string& path) {
  const nlohmann::json j = readJsonFile(path, "--script");
  if (!j.is_array()) fail("--script '", path, "': expected a JSON list of events");
  static const std::vector<std::string> kinds = {
      "frames", "orbit",      "move",  "reset_camera",      "method",     "set",  "show",
      "time",   "screenshot", "scene", "window_screenshot", "light_face", "light"};
  std::vector<ScriptEvent> events;
  for (size_t i = 0; i < j.size(); ++i) {
    const std::string where = "--script '" + path + "' event " + std::to_string(i);
    if (!j[i].is_object() || j[i].size() != 1) fail(where, ": expected {\"kind\": value}, not ", j[i].dump());
    const std::string kind = j[i].begin().key();
    const nlohmann::json& v = j[i].begin().value();
    if (std::find(kinds.begin(), kinds.end(), kind) == kinds.end()) {
      std::string list;
      for (auto& k : kinds) list += (list.empty() ? "" : ", ") + k;
      fail(where, ": unknown event '", kind, "' (known: ", list, ")");
    }
    auto numbers = [&](size_t n) {
      if (!v.is_array() || v.size() != n) fail(where, ": '", kind, "' needs ", n, " numbers, not ", v.dump());
      for (auto& x : v)
        if (!x.is_number() || !finiteAsFloat(x.get<double>()))
          fail(where, ": '", kind, "' = ", v.dump(), " has a value that is not a finite 32-bit float");
    };
    if (kind == "frames" && (!v.is_number_integer() || v.get<long>() < 1 || v.get<long>() > 1000000))
      fail(where, ": 'frames' = ", v.dump(), " must be an integer in [1, 1000000]");
    if (kind == "light_face" && (!v.is_number_integer() || v.get<long>() < 0 || v.get<long>() > 1000000))
      fail(where, ": 'light_face' = ", v.dump(), " must be an integer in [0, 1000000]");
    if (kind == "orbit") numbers(2);
    if (kind == "move") numbers(3);
    if ((kind == "method" || kind == "show" || kind == "screenshot" || kind == "scene" ||
         kind == "window_screenshot" || kind == "light") &&
        !v.is_string())
      fail(where, ": '", kind, "' = ", v.dump(), " must be a string");
    if (kind == "set" && !v.is_object())
      fail(where, ": 'set' = ", v.dump(), " must be an object of parameters");
    if (kind == "set")
      for (auto& [k, x] : v.items()) {
        std::string text;
        if (!paramTextOf(x, text))
          fail(where, ": 'set.", k, "' = ", x.dump(), " must be a number, string or bool");
      }
    if (kind == "time" && (!v.is_number() || !finiteAsFloat(v.get<double>())))
      fail(where, ": 'time' = ", v.dump(), " must be a finite 32-bit float");
    if (kind == "screenshot") checkOutputPath(v.get<std::string>());
    if (kind == "light") {
      try {
        parseLightPosition(v.get<std::string>());
      } catch (const Error& e) {
        fail(where, ": ", e.what());
      }
    }
    if (kind == "window_screenshot") checkOutputFile(v.get<std::string>(), where + " window_screenshot");
    events.push_back({v, kind, i});
  }
  return events;
}

std::string setText(const nlohmann::json& v) {
  std::string text;
  if (!paramTextOf(v, text)) fail("'", v.dump(), "' is not a number, string or bool");
  return text;
}

}  // namespace vgi::app
