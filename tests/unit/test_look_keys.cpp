// The shared look keys (generators/model/look_keys.h): every method accepts every one of them,
// each changes that method's model in the field it names, and none touches the skeleton (the
// look is the model stage's, the skeleton pass keeps all the randomness). One test per method
// so that ctest runs them in parallel; the built-in presets are shrunk where they are slow,
// since the look does not depend on the size of the tree.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "generators/core/input_error.h"
#include "generators/core/toml_reader.h"
#include "generators/model/look_keys.h"
#include "generators/species/registry.h"

using namespace forest;

namespace {

// Sets a top-level key of a species text: replaces its line, or adds it after `method`.
std::string set_key(std::string text, const std::string& key, const std::string& value) {
  size_t at = 0;
  while (at < text.size() && text[at] != '[') {  // top-level keys come before any table
    size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(at, end - at);
    size_t eq = line.find('=');
    if (eq != std::string::npos && line.compare(0, key.size(), key) == 0 &&
        line.find_first_not_of(' ', key.size()) == eq)
      return text.replace(at, end - at, key + " = " + value);
    at = end + 1;
  }
  return text.insert(text.find('\n') + 1, key + " = " + value + "\n");
}

// The built-in preset, made small: the smaller skeleton keeps the test fast.
std::string small_preset(const std::string& method) {
  static const std::map<std::string, std::vector<std::pair<std::string, std::string>>> kShrink = {
      {"lsystem", {{"iterations", "4"}}},
      {"particle-flow", {{"particles", "150"}, {"iterations", "60"}}},
      {"visual-hull", {{"years", "2"}, {"voxels", "24"}}},
      {"sketch-mrf", {{"generations", "1"}, {"em_iterations", "2"}, {"synthetic_generations", "2"}}},
      {"silhouettes", {{"levels", "2"}, {"max_branches", "300"}}},
      {"mig", {{"nodes", "800"}}},
      {"mgv", {{"nodes", "3000"}}},
      {"magnetic", {{"max_curves", "12"}}},
      {"plantons", {{"max_organs", "400"}}},
  };
  std::string text = default_species_text(method);
  if (auto it = kShrink.find(method); it != kShrink.end())
    for (const auto& [key, value] : it->second) text = set_key(text, key, value);
  return text;
}

struct Generated {
  TreeModel model;
  TreeGraph skeleton;
};

Generated generate(const std::string& text, const std::string& name) {
  Generated g;
  GenerateOptions options;
  options.skeleton = &g.skeleton;
  g.model = generate_from_species_text(text, name, options);
  return g;
}

// One failure naming the first node or leaf that differs (not one per node).
void expect_same_skeleton(const TreeGraph& a, const TreeGraph& b, const std::string& what) {
  ASSERT_EQ(a.nodes.size(), b.nodes.size()) << what;
  ASSERT_EQ(a.leaves.size(), b.leaves.size()) << what;
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    const TreeNode &p = a.nodes[i], &q = b.nodes[i];
    if (p.position != q.position || p.radius != q.radius || p.parent != q.parent)
      return ADD_FAILURE() << what << ": skeleton node " << i << " differs";
  }
  for (size_t i = 0; i < a.leaves.size(); ++i) {
    const LeafPlacement &p = a.leaves[i], &q = b.leaves[i];
    if (p.position != q.position || p.rotation != q.rotation || p.scale != q.scale || p.color != q.color)
      return ADD_FAILURE() << what << ": leaf " << i << " differs";
  }
}

// A value of each look key that no built-in preset uses, and what it must change.
struct LookChange {
  std::string value;
  void (*expect)(const TreeModel& base, const TreeModel& changed, const std::string& what);
};
const std::map<std::string, LookChange>& look_changes() {
  static const std::map<std::string, LookChange> kChanges = {
      {"leaf_shape",
       {"\"lanceolate\"",
        [](const TreeModel& base, const TreeModel& changed, const std::string& what) {
          EXPECT_EQ(changed.meta["leaf_shape"], "lanceolate") << what;
          EXPECT_NE(changed.leaf_texture.rgba, base.leaf_texture.rgba) << what;
          EXPECT_NE(changed.leaf_card.vertices[1].position, base.leaf_card.vertices[1].position) << what;
        }}},
      {"bark_color",
       {"[0.5, 0.4, 0.3]",
        [](const TreeModel& base, const TreeModel& changed, const std::string& what) {
          EXPECT_EQ(changed.bark_color, glm::vec3(0.5f, 0.4f, 0.3f)) << what;
          EXPECT_NE(changed.bark_color, base.bark_color) << what;
          EXPECT_NE(changed.bark_texture.rgba, base.bark_texture.rgba) << what;  // the albedo holds it
        }}},
      // Another texture and normal map, and bark uv in its tile size.
      {"bark_pattern",
       {"\"birch\"",
        [](const TreeModel& base, const TreeModel& changed, const std::string& what) {
          EXPECT_EQ(changed.meta["bark_pattern"], "birch") << what;
          EXPECT_EQ(base.meta["bark_pattern"], "generic") << what;
          EXPECT_NE(changed.bark_texture.rgba, base.bark_texture.rgba) << what;
          EXPECT_NE(changed.bark_normal.rgba, base.bark_normal.rgba) << what;
          EXPECT_EQ(changed.bark_tile_meters, bark_tile_meters(BarkPattern::birch)) << what;
          EXPECT_EQ(base.bark_tile_meters, bark_tile_meters(BarkPattern::generic)) << what;
        }}},
      {"leaf_color",
       {"[0.3, 0.6, 0.2]",
        [](const TreeModel& base, const TreeModel& changed, const std::string& what) {
          EXPECT_EQ(changed.leaf_color, glm::vec3(0.3f, 0.6f, 0.2f)) << what;
          EXPECT_NE(changed.leaf_color, base.leaf_color) << what;
        }}},
      // Thin chains get more sides: more branch vertices.
      {"ring_sides_min",
       {"6",
        [](const TreeModel& base, const TreeModel& changed, const std::string& what) {
          EXPECT_GT(changed.branches.vertices.size(), base.branches.vertices.size()) << what;
        }}},
      // The trunk (and the chains near its radius) get more sides.
      {"ring_sides_max",
       {"12",
        [](const TreeModel& base, const TreeModel& changed, const std::string& what) {
          EXPECT_GT(changed.branches.vertices.size(), base.branches.vertices.size()) << what;
        }}},
  };
  return kChanges;
}

std::string test_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

class LookKeysEveryMethod : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST(LookKeys, EveryKeyHasAChangeTest) {
  // A key added to kLookKeys without a value in look_changes() would go untested.
  ASSERT_EQ(look_changes().size(), std::size(kLookKeys));
  for (std::string_view key : kLookKeys) EXPECT_TRUE(look_changes().count(std::string(key))) << key;
}

TEST(LookKeys, OneSetOfDefaults) {
  TomlDocument doc = TomlDocument::parse("method = \"lsystem\"\n", "d.toml");
  LookKeys read = read_look_keys(doc.root()), defaults;
  EXPECT_EQ(read.leaf_shape, defaults.leaf_shape);
  EXPECT_EQ(read.bark_pattern, defaults.bark_pattern);
  EXPECT_EQ(defaults.bark_pattern, BarkPattern::generic);
  EXPECT_EQ(read.bark_color, defaults.bark_color);
  EXPECT_EQ(read.leaf_color, defaults.leaf_color);
  EXPECT_EQ(read.ring_sides_min, defaults.ring_sides_min);
  EXPECT_EQ(read.ring_sides_max, defaults.ring_sides_max);
  EXPECT_EQ(defaults.leaf_shape, LeafShape::ovate);
  EXPECT_EQ(defaults.ring_sides_min, 3);
  EXPECT_EQ(defaults.ring_sides_max, 8);
}

TEST_P(LookKeysEveryMethod, EachKeyChangesTheModelNotTheSkeleton) {
  const std::string method = GetParam();
  const std::string base_text = small_preset(method);
  Generated base = generate(base_text, method + ".toml");
  ASSERT_GT(base.model.branches.vertices.size(), 0u) << method;
  for (const auto& [key, change] : look_changes()) {
    const std::string what = method + " " + key + " = " + change.value;
    Generated changed = generate(set_key(base_text, key, change.value), method + ".toml");
    change.expect(base.model, changed.model, what);
    expect_same_skeleton(base.skeleton, changed.skeleton, what);
  }
}

TEST_P(LookKeysEveryMethod, BadValuesNameFileLineAndKey) {
  const std::string method = GetParam();
  const std::string base_text = small_preset(method);
  const std::pair<const char*, const char*> kBad[] = {
      {"leaf_shape", "\"maple\""},  {"bark_pattern", "\"oak\""},   {"bark_pattern", "3"},
      {"bark_color", "[0.5, 0.5]"},   {"leaf_color", "[0.1, 2.0, 0.1]"},
      {"ring_sides_min", "2"},      {"ring_sides_max", "33"},       {"ring_sides_max", "2.5"}};
  for (const auto& [key, value] : kBad) {
    std::string text = set_key(base_text, key, value);
    int line = 1 + int(std::count(text.begin(), text.begin() + text.find(std::string(key) + " = "), '\n'));
    try {
      generate_from_species_text(text, "bad.toml");
      ADD_FAILURE() << method << ": no error for " << key << " = " << value;
    } catch (const InputError& e) {
      std::string msg = e.what();
      EXPECT_NE(msg.find("bad.toml:" + std::to_string(line) + ": " + key + ":"), std::string::npos) << msg;
    }
  }
  // min above max names the second key.
  std::string crossed = set_key(set_key(base_text, "ring_sides_min", "9"), "ring_sides_max", "5");
  EXPECT_THROW(
      try { generate_from_species_text(crossed, "bad.toml"); } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("ring_sides_max: must be >= ring_sides_min"), std::string::npos) << e.what();
        throw;
      },
      InputError);
}

INSTANTIATE_TEST_SUITE_P(Methods, LookKeysEveryMethod, ::testing::ValuesIn(method_ids()), test_name);
