// The species cache's key and records: every file a preset names is in the key, and
// check_entry tells ok, stale and corrupt entries apart.
#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>

#include "engine/tools/bake/build_identity.h"
#include "engine/tools/bake/cache_record.h"
#include "engine/tools/bake/species_cache.h"
#include "generators/asset/asset_io.h"
#include "generators/core/content_hash.h"
#include "generators/core/input_error.h"
#include "generators/species/registry.h"
#include "generators/species/species_inputs.h"
#include "tests/common/test_files.h"

using namespace forest;
using namespace forest::test;
namespace fs = std::filesystem;

namespace {

// scenes/species/visual_hull_cone.toml and its inputs, copied under `root` with the same
// relative layout (species/, inputs/visual-hull/cone/).
fs::path copy_cone(const fs::path& root) {
  fs::create_directories(root / "species");
  fs::create_directories(root / "inputs/visual-hull");
  fs::copy_file(kSourceDir + "/scenes/species/visual_hull_cone.toml", root / "species/cone.toml");
  fs::copy(kSourceDir + "/scenes/inputs/visual-hull/cone", root / "inputs/visual-hull/cone", fs::copy_options::recursive);
  return root / "species/cone.toml";
}

}  // namespace

TEST(SpeciesInputs, FollowsEveryFileAPresetNamesAndTheFilesThoseName) {
  std::vector<SpeciesInput> in = species_inputs(kSourceDir + "/scenes/species/visual_hull_cone.toml");
  ASSERT_GE(in.size(), 10u);  // the preset, views.json, 8 masks
  EXPECT_EQ(in[0].name, "visual_hull_cone.toml");
  EXPECT_EQ(in[1].name, "../inputs/visual-hull/cone/views.json");
  size_t masks = 0;
  for (const SpeciesInput& i : in) masks += i.name.ends_with(".png");
  EXPECT_EQ(masks, 8u);
  // Particle flow: views_svg.json names SVG attractors beside it.
  size_t svgs = 0;
  for (const SpeciesInput& i : species_inputs(kSourceDir + "/scenes/species/particle_flow_poplar.toml"))
    svgs += i.name.ends_with(".svg");
  EXPECT_EQ(svgs, 2u);
  // An L-system names no file: the preset alone.
  EXPECT_EQ(species_inputs(kSourceDir + "/scenes/species/broadleaf.toml").size(), 1u);
}

TEST(SpeciesCache, EditingAFileThePresetNamesChangesTheKeyMovingTheProjectDoesNot) {
  fs::path dir = fresh_temp_dir("cache_inputs");
  SpeciesDesc s;
  s.preset = copy_cone(dir / "a");
  BakeDesc b;
  std::string key = species_cache_key(s, b);
  // The whole project elsewhere: names are relative, so the same key.
  SpeciesDesc moved;
  moved.preset = copy_cone(dir / "b");
  EXPECT_EQ(species_cache_key(moved, b), key);
  // One mask edited (an ellipsoid's mask of the same size over it): a new key.
  fs::copy_file(kSourceDir + "/scenes/inputs/visual-hull/ellipsoid/view0.png", dir / "b/inputs/visual-hull/cone/view0.png",
                fs::copy_options::overwrite_existing);
  EXPECT_NE(species_cache_key(moved, b), key);
  // The key names what it hashed: the preset first, absolute paths, content hashes.
  SpeciesKey k = species_key(s, b);
  ASSERT_FALSE(k.inputs.empty());
  EXPECT_TRUE(fs::path(k.inputs[0].file).is_absolute());
  EXPECT_EQ(k.inputs[0].hash, content_hash(slurp(s.preset)));
  EXPECT_EQ(std::string(bake_build_identity()).size(), 32u);
  EXPECT_GT(bake_build_sources(), 100);
  fs::remove_all(dir);
}

TEST(CacheRecord, RoundTripsAndCheckEntryTellsOkStaleAndCorrupt) {
  fs::path dir = fresh_temp_dir("cache_record");
  SpeciesDesc s;
  s.preset = dir / "p.toml";
  fs::copy_file(kSourceDir + "/scenes/species/fig2_1.toml", s.preset);
  BakeDesc b;
  SpeciesKey k = species_key(s, b);
  fs::path entry = species_cache_file(s, k.key, dir / "cache");
  fs::create_directories(entry.parent_path());
  save_glb(generate_from_species(s.preset, {}), entry);
  std::string bytes = slurp(entry);
  CacheRecord r;
  r.key = k.key;
  r.preset = k.inputs[0].file;
  r.bake = b;
  r.inputs = k.inputs;
  r.build = bake_build_identity();
  r.device = "test device";
  r.driver = "test driver";
  r.asset_bytes = bytes.size();
  r.asset_hash = content_hash(bytes);
  std::string json = record_json(r);
  EXPECT_EQ(record_json(parse_record(json, "r.json")), json);
  EXPECT_THROW(parse_record("{\"format\": 3}", "r.json"), InputError);
  EXPECT_THROW(parse_record("not json", "r.json"), InputError);
  auto write = [](const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; };
  write(record_path(entry), json);
  ASSERT_EQ(cache_entries(dir / "cache"), std::vector<fs::path>{entry});
  EXPECT_EQ(check_entry(entry).state, EntryState::ok) << check_entry(entry).why;
  // Another build made it: stale.
  CacheRecord other = r;
  other.build = std::string(32, '0');
  write(record_path(entry), record_json(other));
  EXPECT_EQ(check_entry(entry).state, EntryState::stale);
  write(record_path(entry), json);
  // An input edited: stale, naming it.
  std::ofstream(s.preset, std::ios::app) << "\n# edited\n";
  EntryCheck edited = check_entry(entry);
  EXPECT_EQ(edited.state, EntryState::stale);
  EXPECT_NE(edited.why.find("p.toml"), std::string::npos) << edited.why;
  // The .glb cut short: corrupt, whatever the inputs.
  write(entry, bytes.substr(0, bytes.size() / 2));
  EXPECT_EQ(check_entry(entry).state, EntryState::corrupt);
  // No record: corrupt.
  write(entry, bytes);
  fs::remove(record_path(entry));
  EXPECT_EQ(check_entry(entry).state, EntryState::corrupt);
  fs::remove_all(dir);
}

// Writers of one file at once (threads here; processes and machines differ only in the
// temporary name's pid and host): a reader never sees anything but one writer's whole
// bytes, and no temporary file stays.
TEST(CacheRecord, ConcurrentWritersOfOneFileLeaveOneWholeFile) {
  fs::path dir = fresh_temp_dir("atomic_writers");
  fs::path file = dir / "entry.glb";
  constexpr int kWriters = 4, kRounds = 12;
  std::vector<std::vector<uint8_t>> contents;
  for (int w = 0; w < kWriters; ++w) contents.emplace_back(size_t(2 << 20) + size_t(w) * 4099, uint8_t(w + 1));
  std::atomic<bool> done{false};
  std::atomic<int> bad_reads{0}, reads{0};
  std::thread reader([&] {
    while (!done) {
      std::string got = slurp(file);
      if (got.empty()) continue;
      reads++;
      bool whole = false;
      for (const auto& c : contents)
        whole |= got.size() == c.size() && std::memcmp(got.data(), c.data(), c.size()) == 0;
      bad_reads += !whole;
    }
  });
  std::vector<std::thread> writers;
  std::atomic<int> failures{0};
  for (int w = 0; w < kWriters; ++w)
    writers.emplace_back([&, w] {
      for (int r = 0; r < kRounds; ++r) try {
          write_file_atomic(file, contents[size_t(w)]);
        } catch (const InputError&) {
          failures++;
        }
    });
  for (std::thread& t : writers) t.join();
  done = true;
  reader.join();
  EXPECT_EQ(failures, 0);
  EXPECT_EQ(bad_reads, 0) << "of " << reads << " reads";
  EXPECT_GT(reads, 0);
  size_t files = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 1u);
  fs::remove_all(dir);
}
