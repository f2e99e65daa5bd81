#include "core/output_files.h"

#include <climits>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/json_text.h"

namespace fs = std::filesystem;

namespace vgi {

void checkOutputFile(const std::string& path, const std::string& option) {
  if (path.empty()) fail(option, ": the path is empty");
  const fs::path file(path);
  // Every name component must fit the file system: ask it now, not after the render.
  const long nameMax = NAME_MAX;
  for (const fs::path& part : file)
    if (part.native().size() > size_t(nameMax))
      fail(option, " '", path, "': the name component '", part.native().substr(0, 40), "…' is ",
           part.native().size(), " bytes long; the limit is ", nameMax);

  std::error_code ec;
  const fs::path dir = file.parent_path();
  if (!dir.empty()) {
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir)) {
      std::error_code isDir;
      fail(option, " '", path, "': cannot create folder '", dir.string(), "': ",
           ec                       ? ec.message()
           : fs::exists(dir, isDir) ? "a file of that name is in the way"
                                    : "unknown reason");
    }
  }
  const fs::file_status st = fs::status(file, ec);
  if (ec && ec != std::errc::no_such_file_or_directory) fail(option, " '", path, "': ", ec.message());
  if (fs::is_directory(st)) fail(option, " '", path, "' is a directory, not a file");
}

void writeTextFile(const std::string& text, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out)
    fail("cannot write '", path, "'", std::filesystem::is_directory(path) ? ": it is a directory" : "");
}

void writeJsonFile(const nlohmann::json& j, const std::string& path) {
  // Whole before the file is opened: never a half-written file.
  writeTextFile(jsonText(j, 2) + "\n", path);
}

}  // namespace vgi
