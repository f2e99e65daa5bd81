// The parts of `vgi sweep` that its files share (experiments/sweep.h is the public face): the
// experiment file's checked readers, where a render's files lie, and the methods' expansion into
// points. sweep_spec.cpp reads a file, sweep_expand.cpp turns its methods into points, references
// and curves, sweep_run.cpp runs what is not done, sweep_results.cpp collects and writes the rows.
#pragma once
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "core/error.h"
#include "experiments/sweep.h"

namespace vgi::sweep_detail {

// A JSON scalar as `--set` text; anything else is refused naming the key.
std::string paramText(const nlohmann::json& v, const std::string& key);
// Refuses a key of `obj` (JSON path `where`) that is not in `known`, listing those.
void checkKeys(const nlohmann::json& obj, const std::string& where, const std::set<std::string>& known);
// v as an integer in [lo, hi], or refused naming `key`.
int intIn(const nlohmann::json& v, const std::string& key, int lo, int hi);
// The string at obj[key] (JSON path `where`), or `def` where the key is absent.
std::string stringAt(const nlohmann::json& obj, const std::string& key, const std::string& where,
                     const std::string& def = "");
// v as a positive (or, with zeroAllowed, non-negative) finite number, or refused naming `key`.
double positive(const nlohmann::json& v, const std::string& key, bool zeroAllowed = false);

// A render's stem: its EXR's path without the extension.
std::string stemOfRender(const SweepRender& r);
// A render's stats JSON, or null where it is missing or torn (a render killed while writing it).
nlohmann::json readJson(const std::string& path);
// A stats file whose fields are not what vgi writes (a run half-wrote it, another tool wrote it): its
// render counts as not done, and the person is told which file, key and value (a warning, once).
void notDone(const Error& e);
// The most samples a render takes (`--spp`, RenderOptions).
constexpr long long kMaxSpp = 1 << 20;

// What expanding the methods gathers across them.
struct ExpandState {
  std::map<std::string, CounterpartChoice> curveMethods;  // method, reference → its curve's method, device
  std::set<std::string> written;                          // the outputs the methods write
};
// Entry `mi` of "methods": its points (scenes × grid combinations), each with its reference and curve.
void expandMethod(const nlohmann::json& j, size_t mi, const nlohmann::json& ref, int refSpp, Experiment& e,
                  ExpandState& st);

}  // namespace vgi::sweep_detail
