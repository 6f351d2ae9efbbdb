// Determinism of every modeling method: the built-in preset of each method, generated twice
// with the same seed, gives byte-identical .glb files, and so does the CPU part of the bake
// (metaball hull + combined priority order) of each. One test per method so that ctest runs
// them in parallel (each method's preset takes 0.3 to 0.9 s to generate).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "generators/asset/asset_io.h"
#include "generators/bake/hull/hull.h"
#include "generators/bake/priority/priority.h"
#include "generators/species/registry.h"

using namespace forest;

namespace {

TreeModel generate(const std::string& method, uint64_t seed) {
  return generate_from_species_text(default_species_text(method), method + ".toml", {seed});
}

void bake_on_cpu(TreeModel& m, uint64_t seed) {
  Hull hull = build_hull(m.leaves, plant_height(m));
  attach_hull(m, hull);
  apply_priority(m, hull, Priority::combined, seed);
}

class Determinism : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(Determinism, SameSeedSameBytes) {
  const std::string method = GetParam();
  TreeModel a = generate(method, 7), b = generate(method, 7);
  std::vector<uint8_t> ga = encode_glb(a), gb = encode_glb(b);
  ASSERT_GT(ga.size(), 1000u);
  EXPECT_TRUE(ga == gb) << method << ": two runs with seed 7 give different .glb files";
  bake_on_cpu(a, 7);
  bake_on_cpu(b, 7);
  EXPECT_FALSE(a.hull.indices.empty()) << method;
  EXPECT_TRUE(encode_glb(a) == encode_glb(b)) << method << ": two bakes with seed 7 differ";
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, Determinism, ::testing::ValuesIn(method_ids()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });
