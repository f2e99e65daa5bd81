// The fields of a JSON object a file gave — a job, a render's stats read back by a sweep or a
// benchmark — each checked as it is read: a value of the wrong type or outside its range is a
// vgi::Error naming the origin, the key and what was found ("job 'a.json': 'spp' = \"1\" must be an
// integer in [1, 1048576]"), never nlohmann's type_error (an internal error, exit 3). A key that is
// absent (or null) gives the default.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace vgi {

class JsonFields {
 public:
  // `origin` names the object in messages ("job 'a.json'", "'DIR/points/p/render.json'"); the object
  // itself is refused when `j` is not one.
  JsonFields(const nlohmann::json& j, std::string origin);

  bool has(const std::string& key) const { return j_.contains(key) && !j_[key].is_null(); }
  const std::string& origin() const { return origin_; }

  std::string text(const std::string& key, const std::string& def) const;
  long long integer(const std::string& key, long long def, long long lo, long long hi) const;
  double number(const std::string& key, double def) const;  // finite
  // A finite number in [lo, hi].
  double numberIn(const std::string& key, double def, double lo, double hi) const;
  bool flag(const std::string& key, bool def) const;
  std::vector<std::string> texts(const std::string& key) const;
  // The object or list at `key` ({} / [] where absent), refused where it is something else.
  const nlohmann::json& object(const std::string& key) const;
  const nlohmann::json& array(const std::string& key) const;
  // The object at `key` as fields of their own, named "ORIGIN key".
  JsonFields fields(const std::string& key) const;

  [[noreturn]] void bad(const std::string& key, const std::string& what) const;

 private:
  const nlohmann::json& j_;
  std::string origin_;
};

}  // namespace vgi
