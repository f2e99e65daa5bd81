#include "core/json_fields.h"

#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/json_text.h"

namespace vgi {

namespace {
const nlohmann::json& emptyObject() {
  static const nlohmann::json o = nlohmann::json::object();
  return o;
}
const nlohmann::json& emptyArray() {
  static const nlohmann::json a = nlohmann::json::array();
  return a;
}
}  // namespace

JsonFields::JsonFields(const nlohmann::json& j, std::string origin) : j_(j), origin_(std::move(origin)) {
  if (!j_.is_object()) fail(origin_, ": expected a JSON object, found ", jsonExcerpt(j_));
}

void JsonFields::bad(const std::string& key, const std::string& what) const {
  fail(origin_, ": '", key, "' = ", has(key) ? jsonExcerpt(j_[key]) : std::string("(missing)"), " ", what);
}

std::string JsonFields::text(const std::string& key, const std::string& def) const {
  if (!has(key)) return def;
  if (!j_[key].is_string()) bad(key, "must be a string");
  return j_[key].get<std::string>();
}

long long JsonFields::integer(const std::string& key, long long def, long long lo, long long hi) const {
  if (!has(key)) return def;
  const nlohmann::json& v = j_[key];
  if (!v.is_number_integer() || (v.is_number_unsigned() && v.get<unsigned long long>() > (1ull << 62)) ||
      v.get<long long>() < lo || v.get<long long>() > hi)
    bad(key, "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return v.get<long long>();
}

double JsonFields::number(const std::string& key, double def) const {
  if (!has(key)) return def;
  if (!j_[key].is_number() || !std::isfinite(j_[key].get<double>())) bad(key, "must be a finite number");
  return j_[key].get<double>();
}

double JsonFields::numberIn(const std::string& key, double def, double lo, double hi) const {
  if (!has(key)) return def;
  const nlohmann::json& v = j_[key];
  if (!v.is_number() || !(v.get<double>() >= lo && v.get<double>() <= hi)) {
    std::ostringstream range;
    range << "must be a number in [" << lo << ", " << hi << "]";
    bad(key, range.str());
  }
  return v.get<double>();
}

bool JsonFields::flag(const std::string& key, bool def) const {
  if (!has(key)) return def;
  if (!j_[key].is_boolean()) bad(key, "must be true or false");
  return j_[key].get<bool>();
}

std::vector<std::string> JsonFields::texts(const std::string& key) const {
  std::vector<std::string> out;
  if (!has(key)) return out;
  if (!j_[key].is_array()) bad(key, "must be a list of strings");
  for (const nlohmann::json& v : j_[key]) {
    if (!v.is_string()) bad(key, "must be a list of strings");
    out.push_back(v.get<std::string>());
  }
  return out;
}

const nlohmann::json& JsonFields::object(const std::string& key) const {
  if (!has(key)) return emptyObject();
  if (!j_[key].is_object()) bad(key, "must be an object");
  return j_[key];
}

const nlohmann::json& JsonFields::array(const std::string& key) const {
  if (!has(key)) return emptyArray();
  if (!j_[key].is_array()) bad(key, "must be a list");
  return j_[key];
}

JsonFields JsonFields::fields(const std::string& key) const {
  return JsonFields(object(key), origin_ + " " + key);
}

}  // namespace vgi
