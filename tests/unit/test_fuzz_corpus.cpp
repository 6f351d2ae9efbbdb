// Replays the fuzzers' seed corpus and every input that once crashed a loader
// (tests/fuzz/corpus/<target>/, tests/fuzz/regressions/<target>/) through the same entry
// points the libFuzzer targets call: each must be accepted or refused with an InputError.
//
// The replay reports how many inputs it ran; that count must equal the number of files in
// the folders, counted here on their own, so an empty, missing or mis-pointed folder (or a
// target the replay cannot find) fails instead of passing having replayed nothing.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/fuzz/fuzz_inputs.h"

namespace fs = std::filesystem;
using namespace forest;

namespace {

std::vector<uint8_t> read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

const fs::path kFuzzDir = fs::path(FOREST_SOURCE_DIR) / "tests" / "fuzz";

// Replays every regular file of tests/fuzz/<folder>/<target>/ through the target; returns how
// many inputs were run.
size_t replay(std::string_view target, const char* folder) {
  const fs::path dir = kFuzzDir / folder / std::string(target);
  size_t n = 0;
  if (!fs::is_directory(dir)) return 0;
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& f : files) {
    for (const fuzz::Target& t : fuzz::targets())
      if (t.name == target) {
        std::vector<uint8_t> bytes = read_bytes(f);
        EXPECT_NO_THROW(t.run(bytes)) << f;
        ++n;
      }
  }
  return n;
}

// The expected count, independently of replay(): regular files under
// FOREST_SOURCE_DIR/tests/fuzz/<folder>/<target>, walked recursively so that a file put in a
// subfolder (which replay would skip) makes the counts differ. 0 when the folder is absent.
size_t files_in(const std::string& folder, std::string_view target) {
  const fs::path dir = fs::path(FOREST_SOURCE_DIR) / "tests/fuzz" / folder / target;
  std::error_code ec;
  if (!fs::exists(dir, ec)) return 0;
  size_t n = 0;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec))
    n += it->is_regular_file() ? 1 : 0;
  EXPECT_FALSE(ec) << dir << ": " << ec.message();
  return n;
}

// `min_regressions`: past crashes committed for this target, which must stay replayed.
void replay_target(std::string_view target, size_t min_regressions = 0) {
  size_t known = 0;
  for (const fuzz::Target& t : fuzz::targets()) known += t.name == target;
  ASSERT_EQ(known, 1u) << "fuzz target '" << target << "' is not (uniquely) registered";

  const size_t corpus_files = files_in("corpus", target);
  const size_t regression_files = files_in("regressions", target);
  EXPECT_GE(corpus_files, 1u) << "no seed corpus in tests/fuzz/corpus/" << target;
  EXPECT_GE(regression_files, min_regressions) << "past crashes missing from tests/fuzz/regressions/" << target;

  const size_t corpus = replay(target, "corpus");
  const size_t regressions = replay(target, "regressions");
  EXPECT_EQ(corpus, corpus_files) << "replayed " << corpus << " of the " << corpus_files
                                  << " files in tests/fuzz/corpus/" << target;
  EXPECT_EQ(regressions, regression_files) << "replayed " << regressions << " of the " << regression_files
                                           << " files in tests/fuzz/regressions/" << target;
}

}  // namespace

TEST(FuzzCorpus, Scene) { replay_target("scene"); }
TEST(FuzzCorpus, Species) { replay_target("species"); }
TEST(FuzzCorpus, Glb) { replay_target("glb", 1); }
TEST(FuzzCorpus, Strokes) { replay_target("strokes", 1); }
TEST(FuzzCorpus, Mask) { replay_target("mask"); }
TEST(FuzzCorpus, Views) { replay_target("views"); }

// Every folder of the corpus and of the regressions belongs to a registered target, and
// every registered target is replayed by a test above: nothing is left out silently.
TEST(FuzzCorpus, EveryFolderIsATarget) {
  std::set<std::string> names;
  for (const fuzz::Target& t : fuzz::targets()) names.insert(std::string(t.name));
  EXPECT_EQ(names, (std::set<std::string>{"scene", "species", "glb", "strokes", "mask", "views"}));
  for (const char* folder : {"corpus", "regressions"}) {
    const fs::path dir = fs::path(FOREST_SOURCE_DIR) / "tests/fuzz" / folder;
    ASSERT_TRUE(fs::is_directory(dir)) << dir;
    size_t subfolders = 0;
    for (const auto& e : fs::directory_iterator(dir)) {
      if (!e.is_directory()) continue;
      ++subfolders;
      EXPECT_TRUE(names.count(e.path().filename().string())) << e.path() << " is no fuzz target";
    }
    EXPECT_GE(subfolders, 1u) << dir;
  }
}
