// JSON as text for files and messages. Strings from user input (material and
// group names, paths) may hold bytes that are not UTF-8; nlohmann's dump()
// throws on those (type error 316) — here they become U+FFFD instead, so a
// stats file is never left half-written by a name. Values quoted in error
// messages are cut short: a 10⁶-element array must not become a 2 MB line.
#pragma once
#include <nlohmann/json_fwd.hpp>
#include <string>

namespace vgi {

// A number with no finite value — a metric whose denominator is 0 (the energy ratio or relative
// error against a black reference, the leak where nothing is lit), a ratio of times that overflowed —
// is the string "undefined" in every file and --json output vgi writes, never null.
constexpr const char* kUndefined = "undefined";
nlohmann::json finiteOrUndefined(double v);  // v, or "undefined" where it is NaN or ±inf

// The text of `j` (indent < 0: one line); non-finite numbers are written as kUndefined.
std::string jsonText(const nlohmann::json& j, int indent = -1);

// At most `limit` characters of the value, "…" marking a cut. Containers are
// summarised by their first elements (never dumped whole: a deep or long value
// costs only what is shown).
std::string jsonExcerpt(const nlohmann::json& j, size_t limit = 80);

// How deeply a scene file may nest arrays and objects (a scene needs 5).
constexpr int kMaxJsonDepth = 64;

// Parses `text`, refusing nesting deeper than kMaxJsonDepth before it is
// built (deep values overflow the stack in copies and messages). Throws
// vgi::Error naming `origin`.
nlohmann::json parseJsonText(const std::string& text, const std::string& origin);

// The JSON file at `path`, read as parseJsonText reads text; throws vgi::Error
// naming `what` and the path when it is not a regular file, cannot be read or
// is not JSON (e.g. readJsonFile(p, "--script") → "--script 'p': …").
nlohmann::json readJsonFile(const std::string& path, const std::string& what);

}  // namespace vgi
