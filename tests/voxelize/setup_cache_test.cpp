// The set-up cache (voxelize/setup_cache.h): an entry reads back as written; a stale, truncated, grown or
// corrupt one is a miss, never used; and a render's grid comes from it the second time, with the same
// image bit for bit, rebuilt when the entry is damaged (issue "Speed on the GL device", step 3).
#include "voxelize/setup_cache.h"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "apps/cli_util.h"
#include "core/error.h"
#include "core/image.h"
#include "test_util.h"

namespace vgi {
namespace fs = std::filesystem;

namespace {
void flipByte(const std::string& file, std::streamoff at) {
  std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
  f.seekg(at);
  char c = 0;
  f.read(&c, 1);
  c = char(c ^ 0x5a);
  f.seekp(at);
  f.write(&c, 1);
}
}  // namespace

TEST(SetupCache, EntriesReadBackAndDamagedOnesAreMisses) {
  const std::string dir = testing::TempDir() + "/setup_cache_unit";
  fs::remove_all(dir);
  std::vector<uint8_t> payload(1000), back;
  for (size_t i = 0; i < payload.size(); ++i) payload[i] = uint8_t(i * 7 + 3);
  EXPECT_FALSE(readSetupCache(dir, "grid", 42, back));  // nothing there yet
  ASSERT_TRUE(writeSetupCache(dir, "grid", 42, payload.data(), payload.size()));
  ASSERT_TRUE(readSetupCache(dir, "grid", 42, back));
  EXPECT_EQ(back, payload);
  EXPECT_FALSE(readSetupCache(dir, "grid", 43, back));   // another key
  EXPECT_FALSE(readSetupCache(dir, "atlas", 42, back));  // another kind
  const std::string file = setupCacheFile(dir, "grid", 42);
  // Renamed to another key's name: the header's key says otherwise.
  fs::copy_file(file, setupCacheFile(dir, "grid", 44));
  EXPECT_FALSE(readSetupCache(dir, "grid", 44, back));
  // One payload byte changed: the digest says so.
  flipByte(file, std::streamoff(fs::file_size(file) - 10));
  EXPECT_FALSE(readSetupCache(dir, "grid", 42, back));
  // Rewritten, then truncated, then grown.
  ASSERT_TRUE(writeSetupCache(dir, "grid", 42, payload.data(), payload.size()));
  fs::resize_file(file, fs::file_size(file) - 1);
  EXPECT_FALSE(readSetupCache(dir, "grid", 42, back));
  ASSERT_TRUE(writeSetupCache(dir, "grid", 42, payload.data(), payload.size()));
  std::ofstream(file, std::ios::app | std::ios::binary) << 'x';
  EXPECT_FALSE(readSetupCache(dir, "grid", 42, back));
  // A header byte changed (the format version): a miss.
  ASSERT_TRUE(writeSetupCache(dir, "grid", 42, payload.data(), payload.size()));
  flipByte(file, 8);
  EXPECT_FALSE(readSetupCache(dir, "grid", 42, back));
  // No cache folder: nothing read or written; an unwritable one only costs time.
  EXPECT_FALSE(writeSetupCache("", "grid", 42, payload.data(), payload.size()));
  EXPECT_FALSE(readSetupCache("", "grid", 42, back));
  EXPECT_FALSE(writeSetupCache("/proc/no_cache_here", "grid", 42, payload.data(), payload.size()));
  // Nothing but entries is left behind (no temporaries).
  for (auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path().extension(), ".bin") << e.path();
}

TEST(SetupCache, TheFolderIsTrimmedOldestFirst) {
  const std::string dir = testing::TempDir() + "/setup_cache_trim";
  fs::remove_all(dir);
  std::vector<uint8_t> payload(100000, 7);
  for (uint64_t key = 1; key <= 5; ++key) {
    ASSERT_TRUE(writeSetupCache(dir, "grid", key, payload.data(), payload.size()));
    fs::last_write_time(setupCacheFile(dir, "grid", key),
                        fs::file_time_type::clock::now() - std::chrono::hours(10 - key));  // 1 oldest
  }
  std::ofstream(dir + "/notes.txt") << "not an entry";
  const uint64_t entry = fs::file_size(setupCacheFile(dir, "grid", 1));
  EXPECT_EQ(trimSetupCache(dir, 3 * entry), 2u);  // 1 and 2 go
  std::vector<uint8_t> back;
  EXPECT_FALSE(readSetupCache(dir, "grid", 1, back));
  EXPECT_FALSE(readSetupCache(dir, "grid", 2, back));
  for (uint64_t key = 3; key <= 5; ++key) EXPECT_TRUE(readSetupCache(dir, "grid", key, back)) << key;
  EXPECT_TRUE(fs::exists(dir + "/notes.txt"));
  EXPECT_EQ(trimSetupCache(dir, 3 * entry), 0u);
  setenv("VGI_CACHE_LIMIT_MB", "5", 1);
  EXPECT_EQ(setupCacheLimit(), 5ull << 20);
  setenv("VGI_CACHE_LIMIT_MB", "lots", 1);  // refused, not read as the default (issue 63)
  EXPECT_THROW(setupCacheLimit(), Error);
  unsetenv("VGI_CACHE_LIMIT_MB");
  EXPECT_EQ(setupCacheLimit(), 2ull << 30);
}

TEST(SetupCache, FilesDigestFollowsNamesAndBytes) {
  const std::string dir = testing::TempDir() + "/setup_cache_digest";
  fs::remove_all(dir);
  fs::create_directories(dir + "/sub");
  std::ofstream(dir + "/a.glsl") << "void main() {}";
  std::ofstream(dir + "/sub/b.glsl") << "x";
  const uint64_t d0 = filesDigest({dir});
  EXPECT_EQ(filesDigest({dir}), d0);
  std::ofstream(dir + "/sub/b.glsl") << "y";
  const uint64_t d1 = filesDigest({dir});
  EXPECT_NE(d1, d0);
  fs::rename(dir + "/sub/b.glsl", dir + "/sub/c.glsl");
  EXPECT_NE(filesDigest({dir}), d1);
}

// A render pays the voxelization once: the second render of a static scene reads the grid (exit 0, the
// stats say "hit", no voxelizer pass ran) and its image equals the first bit for bit; a damaged entry is
// rebuilt and rewritten; value channels' sums are kept beside the grid; the radiance channel and an
// empty VGI_CACHE_DIR turn it off.
TEST(SetupCache, ASecondRenderReadsTheGridAndAFaultyEntryIsRebuilt) {
  const std::string dir = test::tmp("setup_cache_render");
  fs::remove_all(dir);
  auto render = [&](const std::string& stem, const std::string& extra) {
    // voxel_ao on a 64² × 128 grid unless `extra` names the method.
    const std::string what = extra.find("--method") == std::string::npos
                                 ? "--method voxel_ao --set voxels=64x64x128 " + extra
                                 : extra;
    test::CliRun r =
        test::vgi("render " + what + " --size 32x32 --spp 1 --quiet -o " + test::tmp(stem + ".exr"));
    EXPECT_EQ(r.code, 0) << r.output;
    return nlohmann::json::parse(std::ifstream(test::tmp(stem + ".json")));
  };
  setenv("VGI_CACHE_DIR", dir.c_str(), 1);
  const nlohmann::json cold = render("sc_cold", "");
  const nlohmann::json warm = render("sc_warm", "");
  EXPECT_EQ(cold["extra"]["grid"]["cache"], "written") << cold["extra"]["grid"];
  EXPECT_EQ(warm["extra"]["grid"]["cache"], "hit") << warm["extra"]["grid"];
  EXPECT_TRUE(cold["timings_ms"].contains("insertion"));
  EXPECT_FALSE(warm["timings_ms"].contains("insertion"));
  EXPECT_FALSE(warm["timings_ms"].contains("atlas_render"));
  EXPECT_EQ(warm["extra"]["grid"]["voxels_set"], cold["extra"]["grid"]["voxels_set"]);
  EXPECT_EQ(readImage(test::tmp("sc_warm.exr")).pixels, readImage(test::tmp("sc_cold.exr")).pixels);
  // Every grid entry damaged: rebuilt (a miss, written again), the same image.
  size_t damaged = 0;
  for (auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().rfind("grid-", 0) == 0) {
      flipByte(e.path().string(), std::streamoff(fs::file_size(e.path()) / 2));
      ++damaged;
    }
  EXPECT_EQ(damaged, 1u);
  const nlohmann::json again = render("sc_again", "");
  EXPECT_EQ(again["extra"]["grid"]["cache"], "written") << again["extra"]["grid"];
  EXPECT_TRUE(again["timings_ms"].contains("insertion"));
  EXPECT_EQ(readImage(test::tmp("sc_again.exr")).pixels, readImage(test::tmp("sc_cold.exr")).pixels);
  EXPECT_EQ(render("sc_again2", "")["extra"]["grid"]["cache"], "hit");
  // Another grid resolution is another entry.
  EXPECT_EQ(render("sc_other", "--method voxel_ao --set voxels=32x32x128")["extra"]["grid"]["cache"],
            "written");
  // A grid with value channels (voxelpath: normal, albedo, glossy) keeps their sums too: the second
  // render runs neither insertion, and its image is the first's; a damaged sums entry is rebuilt.
  const std::string vp = "--method voxelpath --set voxels=64x64x128";
  const nlohmann::json vpCold = render("sc_vp_cold", vp), vpWarm = render("sc_vp_warm", vp);
  EXPECT_EQ(vpCold["extra"]["grid"]["cache"], "written") << vpCold["extra"]["grid"];
  EXPECT_EQ(vpWarm["extra"]["grid"]["cache"], "hit") << vpWarm["extra"]["grid"];
  EXPECT_TRUE(vpCold["timings_ms"].contains("insertion_values"));
  EXPECT_FALSE(vpWarm["timings_ms"].contains("insertion_values"));
  EXPECT_EQ(readImage(test::tmp("sc_vp_warm.exr")).pixels, readImage(test::tmp("sc_vp_cold.exr")).pixels);
  for (auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().rfind("values-", 0) == 0)
      flipByte(e.path().string(), std::streamoff(fs::file_size(e.path()) - 3));
  EXPECT_EQ(render("sc_vp_again", vp)["extra"]["grid"]["cache"], "written");
  EXPECT_EQ(readImage(test::tmp("sc_vp_again.exr")).pixels, readImage(test::tmp("sc_vp_cold.exr")).pixels);
  // The radiance channel follows the lights: never cached.
  EXPECT_EQ(render("sc_radiance",
                   "--method vct --set voxels=64x64x128 --set radiance=atlas")["extra"]["grid"]["cache"],
            "off");
  // Off: an empty VGI_CACHE_DIR.
  setenv("VGI_CACHE_DIR", "", 1);
  EXPECT_EQ(render("sc_off", "")["extra"]["grid"]["cache"], "off");
  unsetenv("VGI_CACHE_DIR");
}

}  // namespace vgi
