#include "core/params.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "core/error.h"

namespace vgi {

void ParamSet::set(const std::string& key, const std::string& value, const std::string& origin) {
  if (key.empty()) fail(origin, ": empty parameter name (expected key=value)");
  values_[key] = Value{value, origin, false};
}

void ParamSet::setFromString(const std::string& kv, const std::string& origin) {
  auto eq = kv.find('=');
  if (eq == std::string::npos || eq == 0)
    fail(origin, " '", kv, "': expected key=value");
  set(kv.substr(0, eq), kv.substr(eq + 1), origin);
}

const ParamSet::Value* ParamSet::lookup(const std::string& key, const std::string& type,
                                        const std::string& def, const std::string& doc) {
  bool known = false;
  for (auto& d : docs_) known |= d.key == key;
  if (!known) docs_.push_back({key, type, def, doc});
  auto it = values_.find(key);
  if (it == values_.end()) return nullptr;
  it->second.used = true;
  return &it->second;
}

int ParamSet::getInt(const std::string& key, int def, const std::string& doc, int lo, int hi) {
  int v = def;
  if (auto* p = lookup(key, "int", std::to_string(def), doc)) {
    char* end = nullptr;
    errno = 0;
    long x = std::strtol(p->text.c_str(), &end, 10);
    if (p->text.empty() || *end != '\0' || errno == ERANGE)
      fail("parameter '", key, "' (", p->origin, "): '", p->text, "' is not an integer");
    if (x < lo || x > hi)
      fail("parameter '", key, "' (", p->origin, "): ", x, " is out of range [", lo, ", ", hi, "]");
    v = int(x);
  }
  resolved_[key] = v;
  return v;
}

float ParamSet::getFloat(const std::string& key, float def, const std::string& doc, float lo,
                         float hi) {
  float v = def;
  if (auto* p = lookup(key, "float", std::to_string(def), doc)) {
    char* end = nullptr;
    errno = 0;
    double x = std::strtod(p->text.c_str(), &end);
    if (p->text.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(x))
      fail("parameter '", key, "' (", p->origin, "): '", p->text, "' is not a finite number");
    if (x < lo || x > hi)
      fail("parameter '", key, "' (", p->origin, "): ", x, " is out of range [", lo, ", ", hi, "]");
    v = float(x);
  }
  resolved_[key] = v;
  return v;
}

bool ParamSet::getBool(const std::string& key, bool def, const std::string& doc) {
  bool v = def;
  if (auto* p = lookup(key, "bool", def ? "true" : "false", doc)) {
    const std::string& t = p->text;
    if (t == "true" || t == "on" || t == "1") v = true;
    else if (t == "false" || t == "off" || t == "0") v = false;
    else fail("parameter '", key, "' (", p->origin, "): '", t, "' is not a boolean (true/false/on/off/1/0)");
  }
  resolved_[key] = v;
  return v;
}

std::string ParamSet::getString(const std::string& key, const std::string& def,
                                const std::string& doc, const std::vector<std::string>& allowed) {
  std::string v = def;
  std::string type = "string";
  if (!allowed.empty()) {
    type.clear();
    for (auto& a : allowed) type += (type.empty() ? "" : "|") + a;
  }
  if (auto* p = lookup(key, type, def, doc)) {
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
