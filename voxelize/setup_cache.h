// The set-up cache: what does not change between renders of one scene, kept on disk — the atlases'
// charts (voxelize/atlas.h) and a static scene's binary grid (illum/resources/binary_grid.h) — so that a
// second render of the scene pays its set-up once. One file per entry, in defaultSetupCacheDir(), named
// <kind>-<key>.bin; the key is a digest of everything the entry depends on (its caller's business).
// A file holds a header (magic, format version, kind, key, payload size, the payload's FNV-1a digest)
// and the payload. A read checks every field and the digest: a stale, truncated or corrupt entry is a
// miss, never used — the caller builds anew and writes it again. Writes go to a temporary of this
// process and are renamed into place, so two processes building one entry never mix their bytes; an
// unwritable cache only costs time.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vgi {

// $VGI_CACHE_DIR, else $XDG_CACHE_HOME/vgi, else ~/.cache/vgi ("" if none).
std::string defaultSetupCacheDir();

// The entry's file: DIR/<kind>-<key as 16 hex digits>.bin.
std::string setupCacheFile(const std::string& dir, const std::string& kind, uint64_t key);

// The payload of entry (kind, key) when the file is whole and its digest matches; false otherwise
// (missing, another format, another kind or key, truncated, corrupt). `dir` "" : no cache, false.
bool readSetupCache(const std::string& dir, const std::string& kind, uint64_t key,
                    std::vector<uint8_t>& payload);

// Writes entry (kind, key) with `bytes` bytes of payload (atomically: a temporary renamed into place),
// then trims the folder to setupCacheLimit() bytes, the least recently written entries first (every new
// vgi build keys its grids anew, so old builds' entries would otherwise pile up). Returns whether it was
// written; `dir` "" : false; a folder that cannot be made (a file stands there): false, with a warning
// (once); an unwritable one: false.
bool writeSetupCache(const std::string& dir, const std::string& kind, uint64_t key, const void* payload,
                     size_t bytes);

// $VGI_CACHE_LIMIT_MB (a whole number of MiB in [1, 2^40)) in bytes, else (unset) 2 GiB; any other value
// is refused (vgi::Error naming the variable and the value).
uint64_t setupCacheLimit();

// Deletes the oldest entries (*.bin, by modification time) of `dir` until they hold at most `limit`
// bytes; what another process deletes meanwhile is skipped. Returns how many it deleted.
size_t trimSetupCache(const std::string& dir, uint64_t limit);

// A digest of the regular files under `folders` (their paths relative to each folder and their bytes,
// in sorted order): what a cached entry read at run time, e.g. the voxelization shaders.
uint64_t filesDigest(const std::vector<std::string>& folders);

}  // namespace vgi
