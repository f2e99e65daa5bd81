#include "core/json_text.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/error.h"

namespace vgi {

nlohmann::json finiteOrUndefined(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(kUndefined);
}

namespace {
bool hasNonFinite(const nlohmann::json& j) {
  if (j.is_number_float()) return !std::isfinite(j.get<double>());
  if (j.is_structured())
    for (const auto& v : j)
      if (hasNonFinite(v)) return true;
  return false;
}
void replaceNonFinite(nlohmann::json& j) {
  if (j.is_number_float() && !std::isfinite(j.get<double>())) j = kUndefined;
  if (j.is_structured())
    for (auto& v : j) replaceNonFinite(v);
}
}  // namespace

std::string jsonText(const nlohmann::json& j, int indent) {
  auto text = [&](const nlohmann::json& v) {
    return v.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
  };
  if (!hasNonFinite(j)) return text(j);
  nlohmann::json copy = j;  // nlohmann writes NaN and ±inf as null: they become "undefined"
  replaceNonFinite(copy);
  return text(copy);
}

namespace {
struct TooDeep {};

void excerptInto(const nlohmann::json& j, size_t limit, std::string& out) {
  if (out.size() >= limit) return;
  if (j.is_array() || j.is_object()) {
    const bool array = j.is_array();
    out += array ? "[" : "{";
    bool firstItem = true;
    for (auto it = j.begin(); it != j.end() && out.size() < limit; ++it) {
      if (!firstItem) out += ", ";
      firstItem = false;
      if (!array) out += jsonText(it.key()) + ": ";
      excerptInto(*it, limit, out);
    }
    if (out.size() < limit) out += array ? "]" : "}";
    return;
  }
  out += jsonText(j);
}
}  // namespace

std::string jsonExcerpt(const nlohmann::json& j, size_t limit) {
  std::string out;
  excerptInto(j, limit, out);
  if (out.size() < limit) return out;  // whole: every container was closed before the limit
  out.resize(limit);
  // Do not cut a UTF-8 sequence in two.
  while (!out.empty() && (static_cast<unsigned char>(out.back()) & 0xC0) == 0x80) out.pop_back();
  if (!out.empty() && static_cast<unsigned char>(out.back()) >= 0xC0) out.pop_back();
  return out + "…";
}

nlohmann::json parseJsonText(const std::string& text, const std::string& origin) {
  try {
    return nlohmann::json::parse(text, [](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
      if (depth > kMaxJsonDepth) throw TooDeep{};
      return true;
    });
  } catch (const TooDeep&) {
    fail(origin, ": JSON nested deeper than ", kMaxJsonDepth, " levels");
  } catch (const nlohmann::json::parse_error& e) {
    fail(origin, ": malformed JSON: ", e.what());
  }
}

nlohmann::json readJsonFile(const std::string& path, const std::string& what) {
  const std::string origin = what + " '" + path + "'";
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(origin, ": does not exist or is not a regular file");
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) fail(origin, ": cannot be read");
  return parseJsonText(text.str(), origin);
}

}  // namespace vgi
