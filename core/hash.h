// FNV-1a (64-bit) over bytes: the project's one content hash — the atlas cache's file names, the
// sweep's point ids, a grid's digest, a dumped program's name. Not cryptographic; stable across
// machines of one byte order.
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>

namespace vgi {

constexpr uint64_t kFnv1aOffset = 1469598103934665603ull;

// Continues the hash h over n bytes at data.
inline uint64_t fnv1a(const void* data, size_t n, uint64_t h = kFnv1aOffset) {
  const unsigned char* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
  return h;
}
inline uint64_t fnv1a(const std::string& s, uint64_t h = kFnv1aOffset) {
  return fnv1a(s.data(), s.size(), h);
}

// The hash as 16 hex digits (a string: JSON numbers lose 64-bit integers in many readers).
inline std::string hexDigest(uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", (unsigned long long)h);
  return buf;
}

}  // namespace vgi
