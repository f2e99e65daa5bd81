// Parameters given as key=value strings (`--set key=value`, scene presets),
// read by modules with a documented default. As in pbrt-v4, a key that no one
// reads is an error, so a typo never silently falls back to a default.
#pragma once
#include <cmath>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace vgi {

struct ParamDoc {
  std::string key, type, defaultValue, doc;
  double lo = 0, hi = 0;             // int and float: the accepted range
  std::vector<std::string> allowed;  // a string of these values only (empty: any)
};

// Whether x (parsed as a double: JSON, strtod) is a finite 32-bit float, as every number the
// renderer computes with is: 1e300 is finite as a double and +inf as a float.
// A comma-separated option value as its items: "a,b,,c" → {a, b, c}.
inline std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  size_t start = 0;
  for (size_t end; (end = s.find(',', start)) != std::string::npos; start = end + 1)
    if (end > start) out.push_back(s.substr(start, end - start));
  if (start < s.size()) out.push_back(s.substr(start));
  return out;
}

inline bool finiteAsFloat(double x) { return std::abs(x) <= double(std::numeric_limits<float>::max()); }

// A JSON scalar as `--set` text (64 → "64", 0.5 → "0.5", true → "true",
// strings as they are); false for anything else (an array, an object, null).
bool paramTextOf(const nlohmann::json& value, std::string& text);

class ParamSet {
 public:
  // origin names where the value came from ("--set", "preset 'fast'") for errors.
  void set(const std::string& key, const std::string& value, const std::string& origin = "--set");
  // Parses "key=value".
  void setFromString(const std::string& keyEqualsValue, const std::string& origin = "--set");
  bool has(const std::string& key) const { return values_.count(key) != 0; }

  int getInt(const std::string& key, int def, const std::string& doc, int lo, int hi);
  float getFloat(const std::string& key, float def, const std::string& doc, float lo, float hi);
  bool getBool(const std::string& key, bool def, const std::string& doc);
  // allowed lists the accepted values (empty: any string).
  std::string getString(const std::string& key, const std::string& def, const std::string& doc,
                        const std::vector<std::string>& allowed = {});

  // Documents a parameter that this configuration does not read (e.g. one that
  // belongs to another integrator), so --help-module lists it; it stays out of resolved().
  void declare(const std::string& key, const std::string& type, const std::string& def,
               const std::string& doc);

  // Throws naming every key that was set but never read.
  void checkAllUsed(const std::string& context) const;
  // Every parameter that was read, with its resolved value.
  nlohmann::json resolved() const { return resolved_; }
  const std::vector<ParamDoc>& docs() const { return docs_; }

 private:
  struct Value {
    std::string text, origin;
    bool used = false;
  };
  const Value* lookup(const std::string& key, const std::string& type, const std::string& def,
                      const std::string& doc, double lo = 0, double hi = 0,
                      const std::vector<std::string>& allowed = {});
  std::map<std::string, Value> values_;
  std::vector<ParamDoc> docs_;
  nlohmann::json resolved_ = nlohmann::json::object();
};

}  // namespace vgi
