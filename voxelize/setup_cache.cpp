#include "voxelize/setup_cache.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/error.h"
#include "core/hash.h"
#include "core/warnings.h"

namespace fs = std::filesystem;

namespace vgi {

namespace {

constexpr char kMagic[8] = {'v', 'g', 'i', 'c', 'a', 'c', 'h', 'e'};
constexpr uint32_t kFormat = 1;

struct Header {
  char magic[8];
  uint32_t format;
  char kind[20];  // NUL-padded
  uint64_t key;
  uint64_t bytes;
  uint64_t digest;  // FNV-1a of the payload
};

Header headerFor(const std::string& kind, uint64_t key, uint64_t bytes, uint64_t digest) {
  Header h{};
  std::memcpy(h.magic, kMagic, sizeof kMagic);
  h.format = kFormat;
  std::strncpy(h.kind, kind.c_str(), sizeof h.kind - 1);
  h.key = key;
  h.bytes = bytes;
  h.digest = digest;
  return h;
}

}  // namespace

std::string defaultSetupCacheDir() {
  if (const char* d = std::getenv("VGI_CACHE_DIR")) return d;
  if (const char* x = std::getenv("XDG_CACHE_HOME")) return std::string(x) + "/vgi";
  if (const char* h = std::getenv("HOME")) return std::string(h) + "/.cache/vgi";
  return "";
}

std::string setupCacheFile(const std::string& dir, const std::string& kind, uint64_t key) {
  return (fs::path(dir) / (kind + "-" + hexDigest(key) + ".bin")).string();
}

bool readSetupCache(const std::string& dir, const std::string& kind, uint64_t key,
                    std::vector<uint8_t>& payload) {
  if (dir.empty()) return false;
  const std::string file = setupCacheFile(dir, kind, key);
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) return false;
  std::ifstream in(file, std::ios::binary);
  Header h{};
  if (!in.read(reinterpret_cast<char*>(&h), sizeof h)) return false;
  const Header want = headerFor(kind, key, h.bytes, h.digest);
  if (std::memcmp(h.magic, want.magic, sizeof h.magic) != 0 || h.format != want.format ||
      std::memcmp(h.kind, want.kind, sizeof h.kind) != 0 || h.key != key)
    return false;
  const uint64_t size = fs::file_size(file, ec);
  if (ec || size != sizeof h + h.bytes) return false;  // truncated or grown: never trust the rest
  payload.resize(size_t(h.bytes));
  if (!in.read(reinterpret_cast<char*>(payload.data()), std::streamsize(payload.size()))) return false;
  return fnv1a(payload.data(), payload.size()) == h.digest;
}

bool writeSetupCache(const std::string& dir, const std::string& kind, uint64_t key, const void* payload,
                     size_t bytes) {
  if (dir.empty()) return false;
  // A folder that cannot be used costs only time, but the person is told (once).
  auto unusable = [&](const std::string& why) {
    printWarning("the set-up cache folder '" + dir + "' " + why +
                 ": nothing is kept for the next render (VGI_CACHE_DIR moves it; empty turns it off)");
    return false;
  };
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir, ec))
    return unusable("cannot be made (" + (ec ? ec.message() : std::string("a file stands there")) + ")");
  const fs::path file = setupCacheFile(dir, kind, key);
  // A temporary of this process' own: two processes (parallel tests, two renders) building the same
  // entry must not write into one file, or one could rename the other's half-written file into place.
  fs::path tmp = file;
  tmp += "." + std::to_string(getpid()) + ".tmp";
  std::ofstream out(tmp, std::ios::binary);
  if (!out) return unusable("cannot be written");
  const Header h = headerFor(kind, key, bytes, fnv1a(payload, bytes));
  out.write(reinterpret_cast<const char*>(&h), sizeof h);
  out.write(static_cast<const char*>(payload), std::streamsize(bytes));
  out.close();
  if (!out) {
    fs::remove(tmp, ec);
    return false;
  }
  std::error_code renamed;
  fs::rename(tmp, file, renamed);
  if (renamed) fs::remove(tmp, ec);
  if (!renamed) trimSetupCache(dir, setupCacheLimit());
  return !renamed;
}

uint64_t setupCacheLimit() {
  const char* v = std::getenv("VGI_CACHE_LIMIT_MB");
  if (!v) return 2ull << 30;
  // Whole MiB only: "2GB", "0", "-1", "1e3" or "" would be read as something else (strtoull reads
  // "-1" as 2^64 − 1), and a limit silently replaced by the default is a cache the user did not ask for.
  char* end = nullptr;
  errno = 0;
  const unsigned long long mb = std::strtoull(v, &end, 10);
  if (*v < '0' || *v > '9' || end == v || *end != 0 || errno == ERANGE || mb < 1 || mb >= (1ull << 40))
    fail("VGI_CACHE_LIMIT_MB '", v,
         "': must be a whole number of MiB in [1, 1099511627775] (unset, the set-up cache keeps 2048 MiB)");
  return mb << 20;
}

size_t trimSetupCache(const std::string& dir, uint64_t limit) {
  struct Entry {
    fs::file_time_type time;
    uint64_t bytes;
    fs::path path;
  };
  std::vector<Entry> entries;
  uint64_t total = 0;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code e;
    if (it->path().extension() != ".bin" || !it->is_regular_file(e)) continue;
    const uint64_t bytes = it->file_size(e);
    const fs::file_time_type time = it->last_write_time(e);
    if (e) continue;  // gone meanwhile
    entries.push_back({time, bytes, it->path()});
    total += bytes;
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.time < b.time; });
  size_t deleted = 0;
  for (const Entry& e : entries) {
    if (total <= limit) break;
    std::error_code r;
    if (fs::remove(e.path, r)) ++deleted;
    total -= e.bytes;
  }
  return deleted;
}

uint64_t filesDigest(const std::vector<std::string>& folders) {
  uint64_t h = kFnv1aOffset;
  for (const std::string& folder : folders) {
    std::vector<fs::path> files;
    std::error_code ec;
    for (fs::recursive_directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
      if (it->is_regular_file(ec)) files.push_back(it->path());
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) {
      h = fnv1a(fs::relative(f, folder, ec).string(), h);
      std::ifstream in(f, std::ios::binary);
      const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      h = fnv1a(bytes, h);
    }
  }
  return h;
}

}  // namespace vgi
