// forest cache ls | verify | clear | build, as a user runs them: an edited mask makes a new
// bake and the old entry stale; parallel and sharded builds equal a serial one byte for
// byte; two writers of one entry leave one valid entry.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include "tests/cli/cli_run.h"

using namespace forest::test;
namespace fs = std::filesystem;

namespace {

class CacheCliTest : public CliDirTest {};

// Test-sized bakes: one view, the smallest tables, no impostor.
const std::string kQuickBake = " --views 1 --resolution 32 --no-impostor";

std::string preset(const std::string& name) { return "'" + kSourceDir + "/scenes/species/" + name + ".toml'"; }

// Every file of a folder by name, with its bytes.
std::map<std::string, std::string> folder_bytes(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) files[e.path().filename().string()] = slurp(e.path());
  return files;
}

}  // namespace

TEST_F(CacheCliTest, EditingAMaskBakesAgainAndVerifyNamesTheOldEntryStale) {
  fs::create_directories(dir_ / "species");
  fs::create_directories(dir_ / "inputs/visual-hull");
  fs::copy_file(kSourceDir + "/scenes/species/visual_hull_cone.toml", dir_ / "species/cone.toml");
  fs::copy(kSourceDir + "/scenes/inputs/visual-hull/cone", dir_ / "inputs/visual-hull/cone", fs::copy_options::recursive);
  const std::string cache = " --cache '" + (dir_ / "cache").string() + "'";
  const std::string build = forest_command("cache build '" + (dir_ / "species/cone.toml").string() + "'" + kQuickBake + cache);
  Result first = run_captured(build, dir_);
  ASSERT_EQ(first.code, 0) << first.out << first.err;
  EXPECT_NE(first.out.find("1 baked"), std::string::npos) << first.out;
  Result again = run_captured(build, dir_);
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_NE(again.out.find("0 baked, 1 already cached"), std::string::npos) << again.out;
  Result ok = run_captured(forest_command("cache verify" + cache), dir_);
  EXPECT_EQ(ok.code, 0) << ok.out;
  EXPECT_NE(ok.out.find("1 ok, 0 stale, 0 corrupt"), std::string::npos) << ok.out;

  // Edit one mask (an ellipsoid's, same size): the next build bakes a new entry, the old one
  // is stale.
  fs::copy_file(kSourceDir + "/scenes/inputs/visual-hull/ellipsoid/view0.png", dir_ / "inputs/visual-hull/cone/view0.png",
                fs::copy_options::overwrite_existing);
  Result edited = run_captured(build, dir_);
  ASSERT_EQ(edited.code, 0) << edited.err;
  EXPECT_NE(edited.out.find("1 baked"), std::string::npos) << edited.out;
  Result ls = run_captured(forest_command("cache ls" + cache), dir_);
  ASSERT_EQ(ls.code, 0) << ls.err;
  EXPECT_NE(ls.out.find("2 entries"), std::string::npos) << ls.out;
  EXPECT_NE(ls.out.find("../inputs/visual-hull/cone/view0.png"), std::string::npos) << ls.out;
  EXPECT_NE(ls.out.find("measured on"), std::string::npos) << ls.out;
  Result stale = run_captured(forest_command("cache verify" + cache), dir_);
  EXPECT_EQ(stale.code, 1) << stale.out;
  EXPECT_NE(stale.out.find("1 ok, 1 stale, 0 corrupt"), std::string::npos) << stale.out;
  EXPECT_NE(stale.out.find("view0.png changed"), std::string::npos) << stale.out;

  // clear --stale removes the stale entry and keeps the good one; clear removes all.
  Result cleared = run_captured(forest_command("cache clear --stale" + cache), dir_);
  ASSERT_EQ(cleared.code, 0) << cleared.err;
  EXPECT_NE(cleared.out.find("removed 1 stale or corrupt entries"), std::string::npos) << cleared.out;
  Result clean = run_captured(forest_command("cache verify" + cache), dir_);
  EXPECT_EQ(clean.code, 0) << clean.out;
  Result all = run_captured(forest_command("cache clear" + cache), dir_);
  ASSERT_EQ(all.code, 0) << all.err;
  EXPECT_TRUE(fs::is_empty(dir_ / "cache"));
}

TEST_F(CacheCliTest, ParallelAndShardedBuildsEqualASerialOneByteForByte) {
  const std::string presets = preset("fig2_1") + " " + preset("broadleaf") + " " + preset("conifer") + kQuickBake;
  auto cache = [&](const std::string& name) { return " --cache '" + (dir_ / name).string() + "'"; };
  Result serial = run_captured(forest_command("cache build " + presets + " --jobs 1" + cache("serial")), dir_);
  ASSERT_EQ(serial.code, 0) << serial.out << serial.err;
  Result parallel = run_captured(forest_command("cache build " + presets + " --jobs 3" + cache("parallel")), dir_);
  ASSERT_EQ(parallel.code, 0) << parallel.out << parallel.err;
  EXPECT_NE(parallel.out.find("3 jobs"), std::string::npos) << parallel.out;
  for (const char* shard : {"0/2", "1/2"}) {
    Result r = run_captured(forest_command("cache build " + presets + " --shard " + shard + cache("sharded")), dir_);
    ASSERT_EQ(r.code, 0) << r.out << r.err;
  }
  std::map<std::string, std::string> expected = folder_bytes(dir_ / "serial");
  EXPECT_EQ(expected.size(), 6u);  // three .glb, three records
  EXPECT_TRUE(folder_bytes(dir_ / "parallel") == expected);
  EXPECT_TRUE(folder_bytes(dir_ / "sharded") == expected);
  // No progress bar in a pipe: stderr stays empty.
  EXPECT_EQ(parallel.err, "");
}

TEST_F(CacheCliTest, TwoWritersOfOneEntryLeaveOneValidEntry) {
  const std::string one = forest_command("cache build " + preset("broadleaf") + kQuickBake + " --cache '" +
                                         (dir_ / "cache").string() + "'");
  Result both = run_captured("(" + one + " >'" + (dir_ / "a").string() + "' 2>&1 & " + one + " >'" +
                                 (dir_ / "b").string() + "' 2>&1 & wait)",
                             dir_);
  ASSERT_EQ(both.code, 0);
  EXPECT_NE(slurp(dir_ / "a").find("cache build: 1 specs"), std::string::npos) << slurp(dir_ / "a");
  EXPECT_NE(slurp(dir_ / "b").find("cache build: 1 specs"), std::string::npos) << slurp(dir_ / "b");
  std::map<std::string, std::string> files = folder_bytes(dir_ / "cache");
  EXPECT_EQ(files.size(), 2u);  // one .glb and its record, no temporary file left
  Result v = run_captured(forest_command("cache verify --cache '" + (dir_ / "cache").string() + "'"), dir_);
  EXPECT_EQ(v.code, 0) << v.out;
  EXPECT_NE(v.out.find("1 ok"), std::string::npos) << v.out;
}

TEST_F(CacheCliTest, BadShardsAndPresetsExitTwoWithOneLine) {
  const std::string cache = " --cache '" + (dir_ / "cache").string() + "'";
  for (const char* shard : {"2/2", "1", "a/b", "0/0"}) {
    Result r = run_captured(forest_command("cache build " + preset("fig2_1") + " --shard " + shard + cache), dir_);
    EXPECT_EQ(r.code, 2) << shard;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("--shard"), std::string::npos) << r.err;
  }
  Result missing = run_captured(forest_command("cache build '" + (dir_ / "none.toml").string() + "'" + cache), dir_);
  EXPECT_EQ(missing.code, 2);
  EXPECT_EQ(lines(missing.err), 1u) << missing.err;
  EXPECT_NE(missing.err.find("none.toml"), std::string::npos) << missing.err;
  Result nothing = run_captured(forest_command("cache build" + cache), dir_);
  EXPECT_EQ(nothing.code, 2);
  EXPECT_FALSE(fs::exists(dir_ / "cache"));
}
