#include "core/params.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <type_traits>

#include "core/error.h"

namespace vgi {

void ParamSet::set(const std::string& key, const std::string& value, const std::string& origin) {
  if (key.empty()) fail(origin, ": empty parameter name (expected key=value)");
  values_[key] = Value{value, origin, false};
}

void ParamSet::setFromString(const std::string& kv, const std::string& origin) {
  auto eq = kv.find('=');
  if (eq == std::string::npos || eq == 0) fail(origin, " '", kv, "': expected key=value");
  set(kv.substr(0, eq), kv.substr(eq + 1), origin);
}

bool paramTextOf(const nlohmann::json& v, std::string& text) {
  if (v.is_string()) {
    text = v.get<std::string>();
  } else if (v.is_boolean()) {
    text = v.get<bool>() ? "true" : "false";
  } else if (v.is_number_integer()) {
    text = std::to_string(v.get<long long>());
  } else if (v.is_number()) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", v.get<double>());
    text = buf;
  } else {
    return false;
  }
  return true;
}

const ParamSet::Value* ParamSet::lookup(const std::string& key, const std::string& type,
                                        const std::string& def, const std::string& doc, double lo, double hi,
                                        const std::vector<std::string>& allowed) {
  bool known = false;
  for (auto& d : docs_) known |= d.key == key;
  if (!known) docs_.push_back({key, type, def, doc, lo, hi, allowed});
  auto it = values_.find(key);
  if (it == values_.end()) return nullptr;
  it->second.used = true;
  return &it->second;
}

namespace {
// Parses a whole string as a number of type T (strtol/strtod) and checks [lo, hi].
template <typename T>
T parseNumber(const std::string& key, const std::string& origin, const std::string& text, T lo, T hi) {
  char* end = nullptr;
  errno = 0;
  const bool integral = std::is_integral_v<T>;
  double x = integral ? double(std::strtol(text.c_str(), &end, 10)) : std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(x))
    fail("parameter '", key, "' (", origin, "): '", text, "' is not ",
         integral ? "an integer" : "a finite number");
  if constexpr (!std::is_integral_v<T>) {
    // In the parameter's own precision: finite as a double is not enough, and a bound compared in
    // double would refuse itself (0.05 parses to a double just below the float 0.05f).
    if (!finiteAsFloat(x))
      fail("parameter '", key, "' (", origin, "): '", text, "' (", x, ") is not a finite 32-bit float");
    const T v = T(x);
    if (v < lo || v > hi)
      fail("parameter '", key, "' (", origin, "): ", v, " is out of range [", lo, ", ", hi, "]");
    return v;
  }
  if (x < double(lo) || x > double(hi))
    fail("parameter '", key, "' (", origin, "): ", x, " is out of range [", lo, ", ", hi, "]");
  return T(x);
}
}  // namespace

int ParamSet::getInt(const std::string& key, int def, const std::string& doc, int lo, int hi) {
  const Value* p = lookup(key, "int", std::to_string(def), doc, lo, hi);
  int v = p ? parseNumber(key, p->origin, p->text, lo, hi) : def;
  resolved_[key] = v;
  return v;
}

float ParamSet::getFloat(const std::string& key, float def, const std::string& doc, float lo, float hi) {
  const Value* p = lookup(key, "float", std::to_string(def), doc, lo, hi);
  float v = p ? parseNumber(key, p->origin, p->text, lo, hi) : def;
  resolved_[key] = v;
  return v;
}

bool ParamSet::getBool(const std::string& key, bool def, const std::string& doc) {
  bool v = def;
  if (auto* p = lookup(key, "bool", def ? "true" : "false", doc)) {
    const std::string& t = p->text;
    if (t == "true" || t == "on" || t == "1")
      v = true;
    else if (t == "false" || t == "off" || t == "0")
      v = false;
    else
      fail("parameter '", key, "' (", p->origin, "): '", t, "' is not a boolean (true/false/on/off/1/0)");
  }
  resolved_[key] = v;
  return v;
}

std::string ParamSet::getString(const std::string& key, const std::string& def, const std::string& doc,
                                const std::vector<std::string>& allowed) {
  std::string v = def;
  std::string type = "string";
  if (!allowed.empty()) {
    type.clear();
    for (auto& a : allowed) type += (type.empty() ? "" : "|") + a;
  }
  if (auto* p = lookup(key, type, def, doc, 0, 0, allowed)) {
    v = p->text;
    if (!allowed.empty()) {
      bool ok = false;
      for (auto& a : allowed) ok |= a == v;
      if (!ok) fail("parameter '", key, "' (", p->origin, "): '", v, "' is not one of ", type);
    }
  }
  resolved_[key] = v;
  return v;
}

void ParamSet::declare(const std::string& key, const std::string& type, const std::string& def,
                       const std::string& doc) {
  for (auto& d : docs_)
    if (d.key == key) return;
  docs_.push_back({key, type, def, doc, 0, 0, {}});
}

void ParamSet::checkAllUsed(const std::string& context) const {
  std::string unused;
  for (auto& [k, v] : values_)
    if (!v.used) unused += (unused.empty() ? "" : ", ") + k + "=" + v.text + " (" + v.origin + ")";
  if (!unused.empty()) {
    std::string known;
    for (auto& d : docs_) known += (known.empty() ? "" : ", ") + d.key;
    fail(context, ": unknown parameter(s) ", unused, "; known: ", known.empty() ? "none" : known);
  }
}

}  // namespace vgi
