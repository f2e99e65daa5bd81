// Files a command writes: checked (and their folder made) before the work
// that fills them, so a long render is never lost to a bad path at its end.
#pragma once
#include <nlohmann/json_fwd.hpp>
#include <string>

namespace vgi {

// Makes the folder `path` goes into (like mkdir -p) and throws, naming
// `option` and the path, if it cannot be made, if `path` is a folder, or if a
// name component is longer than the file system allows.
void checkOutputFile(const std::string& path, const std::string& option);
// Writes `text` to `path`; throws naming the path (a directory there, a full disk) if it was not written.
void writeTextFile(const std::string& text, const std::string& path);
// Writes `j` (indented; bytes that are not UTF-8 become U+FFFD) to `path`, as writeTextFile.
void writeJsonFile(const nlohmann::json& j, const std::string& path);

}  // namespace vgi
