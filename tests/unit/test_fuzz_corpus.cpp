// Replays the fuzzers' seed corpus and every input that once crashed a loader
// (tests/fuzz/corpus/<target>/, tests/fuzz/regressions/<target>/) through the same entry
// points the libFuzzer targets call: each must be accepted or refused with an InputError.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
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

// Returns how many files were replayed.
size_t replay(std::string_view target, const char* folder) {
  const fs::path dir = fs::path(FOREST_SOURCE_DIR) / "tests/fuzz" / folder / std::string(target);
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

void replay_target(std::string_view target) {
  size_t corpus = replay(target, "corpus");
  EXPECT_GT(corpus, 0u) << "no seed corpus for " << target;
  replay(target, "regressions");
}

}  // namespace

TEST(FuzzCorpus, Scene) { replay_target("scene"); }
TEST(FuzzCorpus, Species) { replay_target("species"); }
TEST(FuzzCorpus, Glb) { replay_target("glb"); }
TEST(FuzzCorpus, Strokes) { replay_target("strokes"); }
TEST(FuzzCorpus, Mask) { replay_target("mask"); }
TEST(FuzzCorpus, Views) { replay_target("views"); }
