// Habit metrics (generators/tree/habit.h) on small hand-built graphs whose answers are known,
// and the presets' [habit] ranges (habit_ranges.h) against their generated trees.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "generators/core/rng.h"
#include "generators/core/input_error.h"
#include "generators/core/toml_reader.h"
#include "generators/species/registry.h"
#include "generators/tree/habit.h"
#include "generators/tree/habit_ranges.h"

using namespace forest;

namespace {

// Appends a node and returns its index.
uint32_t node(TreeGraph& g, glm::vec3 p, float radius, int32_t parent) {
  g.nodes.push_back(TreeNode{p, radius, parent, parent < 0 ? 0u : g.nodes[size_t(parent)].order});
  return uint32_t(g.nodes.size() - 1);
}

void leaf(TreeGraph& g, glm::vec3 p) {
  LeafPlacement l;
  l.position = p;
  g.leaves.push_back(l);
}

// A 10 m excurrent stem (nodes every metre, radius tapering 0.3 → 0.1) with a bare branch at
// 1 m and leafy side branches at 3, 5 and 7 m; the 3 m branch droops, its leaf at 2.5 m.
TreeGraph excurrent() {
  TreeGraph g;
  std::vector<uint32_t> stem;
  for (int y = 0; y <= 10; ++y)
    stem.push_back(node(g, {0.0f, float(y), 0.0f}, 0.3f - 0.02f * float(y), y == 0 ? -1 : int32_t(stem.back())));
  uint32_t bare = node(g, {-1.0f, 1.2f, 0.0f}, 0.05f, int32_t(stem[1]));
  node(g, {-2.0f, 1.4f, 0.0f}, 0.04f, int32_t(bare));
  uint32_t b3 = node(g, {1.0f, 2.9f, 0.0f}, 0.05f, int32_t(stem[3]));
  node(g, {2.0f, 2.6f, 0.0f}, 0.04f, int32_t(b3));
  leaf(g, {2.1f, 2.5f, 0.0f});
  uint32_t b5 = node(g, {0.0f, 5.2f, 1.0f}, 0.05f, int32_t(stem[5]));
  node(g, {0.0f, 5.4f, 1.5f}, 0.04f, int32_t(b5));
  leaf(g, {0.0f, 5.5f, 1.6f});
  uint32_t b7 = node(g, {0.0f, 7.2f, -1.0f}, 0.05f, int32_t(stem[7]));
  node(g, {0.0f, 7.4f, -1.2f}, 0.04f, int32_t(b7));
  leaf(g, {0.0f, 7.5f, -1.3f});
  leaf(g, {-0.9f, 9.5f, 0.0f});  // near the top of the stem itself
  return g;
}

// A 3 m trunk forking into two near-equal stems (radii 0.2 and `second`) reaching 8 and 9 m.
TreeGraph forked(float second) {
  TreeGraph g;
  uint32_t a = node(g, {0.0f, 0.0f, 0.0f}, 0.3f, -1);
  uint32_t f = node(g, {0.0f, 3.0f, 0.0f}, 0.3f, int32_t(a));
  uint32_t l = node(g, {-1.0f, 5.0f, 0.0f}, 0.2f, int32_t(f));
  uint32_t r = node(g, {1.0f, 5.0f, 0.0f}, second, int32_t(f));
  node(g, {-1.5f, 9.0f, 0.0f}, 0.1f, int32_t(l));
  node(g, {1.5f, 8.0f, 0.0f}, 0.1f, int32_t(r));
  leaf(g, {-1.5f, 9.0f, 0.5f});
  leaf(g, {1.6f, 8.0f, -0.5f});
  return g;
}

}  // namespace

TEST(Habit, ExcurrentStemHasASingleLeaderAndAClearBole) {
  HabitMetrics m = measure_habit(excurrent());
  EXPECT_EQ(m.leaves, 4u);
  EXPECT_FLOAT_EQ(m.base_y, 0.0f);
  EXPECT_FLOAT_EQ(m.height, 10.0f);
  EXPECT_EQ(m.stem_nodes, 11u);
  // Leaves span x ∈ [−0.9, 2.1], z ∈ [−1.3, 1.6]; the bare branch's nodes do not count.
  EXPECT_NEAR(m.crown_width_x, 3.0f, 1e-5f);
  EXPECT_NEAR(m.crown_width_z, 2.9f, 1e-5f);
  EXPECT_NEAR(m.crown_width, 2.95f, 1e-5f);
  EXPECT_NEAR(m.crown_ratio, 0.295f, 1e-5f);
  // The lowest leafy branch leaves the stem at 3 m (the bare one at 1 m is dead wood); its
  // drooping leaf is lower, at 2.5 m.
  EXPECT_FLOAT_EQ(m.crown_base, 3.0f);
  EXPECT_FLOAT_EQ(m.clear_bole, 0.3f);
  EXPECT_FLOAT_EQ(m.lowest_leaf, 0.25f);
  EXPECT_FALSE(m.codominant_fork);
  EXPECT_FLOAT_EQ(m.trunk_height, 10.0f);
  EXPECT_FLOAT_EQ(m.trunk_fraction, 1.0f);
  EXPECT_TRUE(m.single_leader);
}

TEST(Habit, HeightsAreMeasuredFromTheRoot) {
  TreeGraph g = excurrent();
  for (TreeNode& n : g.nodes) n.position.y += 2.0f;
  for (LeafPlacement& l : g.leaves) l.position.y += 2.0f;
  HabitMetrics m = measure_habit(g);
  EXPECT_FLOAT_EQ(m.base_y, 2.0f);
  EXPECT_FLOAT_EQ(m.height, 10.0f);
  EXPECT_FLOAT_EQ(m.crown_base, 3.0f);
  EXPECT_FLOAT_EQ(m.lowest_leaf, 0.25f);
}

TEST(Habit, CodominantForkEndsTheTrunk) {
  HabitMetrics m = measure_habit(forked(0.18f));  // 0.18 ≥ 0.7 × 0.2
  EXPECT_FLOAT_EQ(m.height, 9.0f);
  EXPECT_TRUE(m.codominant_fork);
  EXPECT_FLOAT_EQ(m.trunk_height, 3.0f);
  EXPECT_FLOAT_EQ(m.trunk_fraction, 3.0f / 9.0f);
  EXPECT_FALSE(m.single_leader);
  // The stem follows the thicker (0.2) stem to the top: root, fork, left, left tip.
  EXPECT_EQ(main_stem(forked(0.18f)), (std::vector<uint32_t>{0, 1, 2, 4}));
  EXPECT_EQ(m.stem_nodes, 4u);
  // Both leaves hang on branches of the fork: the crown starts there.
  EXPECT_FLOAT_EQ(m.crown_base, 3.0f);
}

TEST(Habit, ForkBelowTheRatioIsNotCodominant) {
  HabitMetrics m = measure_habit(forked(0.139f));  // just under 0.7 × 0.2
  EXPECT_FALSE(m.codominant_fork);
  EXPECT_FLOAT_EQ(m.trunk_fraction, 1.0f);
  EXPECT_TRUE(m.single_leader);
  EXPECT_TRUE(measure_habit(forked(0.141f)).codominant_fork);
}

TEST(Habit, LateCodominantForkKeepsASingleLeader) {
  // The fork at 9 m of a 10 m stem: the stem reached 0.9 H ≥ 0.85 H before it.
  TreeGraph g;
  uint32_t a = node(g, {0.0f, 0.0f, 0.0f}, 0.3f, -1);
  uint32_t f = node(g, {0.0f, 9.0f, 0.0f}, 0.2f, int32_t(a));
  node(g, {-0.3f, 10.0f, 0.0f}, 0.1f, int32_t(f));
  node(g, {0.3f, 9.8f, 0.0f}, 0.1f, int32_t(f));
  HabitMetrics m = measure_habit(g);
  EXPECT_TRUE(m.codominant_fork);
  EXPECT_FLOAT_EQ(m.trunk_fraction, 0.9f);
  EXPECT_TRUE(m.single_leader);
  // A fork at 8 m would not.
  g.nodes[1].position.y = 8.0f;
  EXPECT_FALSE(measure_habit(g).single_leader);
}

TEST(Habit, ZeroRadiiCompareSubtreeSizes) {
  TreeGraph g = forked(0.18f);
  for (TreeNode& n : g.nodes) n.radius = 0.0f;
  // Both arms have two nodes: equal subtrees, codominant.
  EXPECT_TRUE(measure_habit(g).codominant_fork);
  // Three more nodes on the right arm: 2 vs 5 nodes, ratio 0.4.
  uint32_t at = 5;
  for (int k = 0; k < 3; ++k) at = node(g, {1.5f, 8.0f + float(k + 1) * 0.1f, 0.0f}, 0.0f, int32_t(at));
  HabitMetrics m = measure_habit(g);
  EXPECT_FALSE(m.codominant_fork);
  EXPECT_EQ(main_stem(g).back(), at);  // the larger subtree carries the stem
}

TEST(Habit, WithoutLeavesTheBranchesStandIn) {
  TreeGraph g = excurrent();
  g.leaves.clear();
  HabitMetrics m = measure_habit(g);
  EXPECT_EQ(m.leaves, 0u);
  // All nodes: x ∈ [−2, 2], z ∈ [−1.2, 1.5].
  EXPECT_NEAR(m.crown_width_x, 4.0f, 1e-5f);
  EXPECT_NEAR(m.crown_width_z, 2.7f, 1e-5f);
  // The lowest stem node with a side branch: the bare branch at 1 m.
  EXPECT_FLOAT_EQ(m.crown_base, 1.0f);
  EXPECT_FLOAT_EQ(m.lowest_leaf, 0.0f);
}

TEST(Habit, EmptyAndSingleNodeGraphs) {
  HabitMetrics e = measure_habit(TreeGraph{});
  EXPECT_EQ(e.nodes, 0u);
  EXPECT_FLOAT_EQ(e.height, 0.0f);
  EXPECT_FALSE(e.single_leader);
  TreeGraph one;
  node(one, {1.0f, 2.0f, 3.0f}, 0.1f, -1);
  leaf(one, {1.0f, 2.0f, 3.0f});
  HabitMetrics m = measure_habit(one);
  EXPECT_FLOAT_EQ(m.height, 0.0f);
  EXPECT_FLOAT_EQ(m.crown_ratio, 0.0f);  // no division by a zero height
  EXPECT_FLOAT_EQ(m.clear_bole, 0.0f);
  EXPECT_FALSE(m.single_leader);
}

// Many nodes and leaves: the grid's nearest-node search must give the same crown base as
// trying every node.
TEST(Habit, CrownBaseMatchesBruteForceNearestNodes) {
  TreeGraph g;
  Rng rng(5);
  std::vector<uint32_t> stem;
  for (int y = 0; y <= 60; ++y)
    stem.push_back(node(g, {0.0f, 0.25f * float(y), 0.0f}, 0.4f - 0.005f * float(y), y ? int32_t(stem.back()) : -1));
  for (int b = 0; b < 40; ++b) {
    uint32_t at = stem[size_t(10 + b)];
    float angle = float(rng.uniform(0.0, 6.2831853)), droop = float(rng.uniform(-0.3, 0.3));
    for (int k = 1; k <= 12; ++k) {
      glm::vec3 p = g.nodes[stem[size_t(10 + b)]].position + float(k) * 0.2f * glm::vec3(std::cos(angle), droop, std::sin(angle));
      at = node(g, p, 0.03f, int32_t(at));
    }
  }
  for (int i = 0; i < 500; ++i)  // leaves scattered around random branch nodes
    leaf(g, g.nodes[61 + rng.next_u32() % 480].position + glm::vec3(rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1)));
  std::vector<uint32_t> s = main_stem(g);
  ASSERT_EQ(s.size(), 61u);
  std::vector<uint32_t> attach(g.nodes.size());
  for (uint32_t i = 0; i < g.nodes.size(); ++i)
    attach[i] = i < 61 ? i : attach[uint32_t(g.nodes[i].parent)];
  float expected = std::numeric_limits<float>::max();
  for (const LeafPlacement& l : g.leaves) {
    uint32_t best = 0;
    for (uint32_t i = 1; i < g.nodes.size(); ++i)
      if (glm::distance(g.nodes[i].position, l.position) < glm::distance(g.nodes[best].position, l.position)) best = i;
    expected = std::min(expected, g.nodes[attach[best]].position.y);
  }
  HabitMetrics m = measure_habit(g);
  EXPECT_FLOAT_EQ(m.crown_base, expected);
  EXPECT_GE(m.crown_base, 2.0f);
  EXPECT_TRUE(m.single_leader);
}

TEST(Habit, HorizontalExtent) {
  std::vector<glm::vec3> p = {{1, 5, -2}, {-3, 0, 4}, {0, 9, 0}};
  EXPECT_EQ(horizontal_extent(p), glm::vec2(4.0f, 6.0f));
  EXPECT_EQ(horizontal_extent({}), glm::vec2(0.0f));
}

// ---- the presets' [habit] ranges (generators/tree/habit_ranges.h) ----

namespace {

std::optional<HabitRanges> ranges_of_text(const std::string& text) {
  TomlDocument doc = TomlDocument::parse(text, "oak.toml");
  return read_habit_ranges(doc.root());
}

// Expects reading the [habit] table of `text` to fail naming file, line and key.
void expect_habit_error(const std::string& text, int line, const std::string& key) {
  try {
    ranges_of_text(text);
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const InputError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("oak.toml:" + std::to_string(line) + ":"), std::string::npos) << msg;
    EXPECT_NE(msg.find(key), std::string::npos) << msg;
  }
}

}  // namespace

TEST(HabitRanges, ReadsTheTable) {
  EXPECT_FALSE(ranges_of_text("method = \"lsystem\"\n").has_value());
  std::optional<HabitRanges> r = ranges_of_text(
      "method = \"lsystem\"\n[habit]\ncrown_width_over_height = [0.6, 1]\nclear_bole_over_height = [0.1, 0.3]\n"
      "trunk_fraction_min = 0.25\nsingle_leader = true\nlowest_leaf_over_height_min = 0.2\n");
  ASSERT_TRUE(r.has_value());
  EXPECT_DOUBLE_EQ(r->crown_ratio->x, 0.6);
  EXPECT_DOUBLE_EQ(r->crown_ratio->y, 1.0);
  EXPECT_DOUBLE_EQ(r->clear_bole->y, 0.3);
  EXPECT_DOUBLE_EQ(*r->trunk_fraction_min, 0.25);
  EXPECT_TRUE(r->single_leader);
  EXPECT_DOUBLE_EQ(*r->lowest_leaf_min, 0.2);
}

TEST(HabitRanges, BadInputNamesFileLineAndKey) {
  const std::string head = "method = \"lsystem\"\n[habit]\n";
  expect_habit_error(head + "crown_width_over_height = [1.0, 0.6]\n", 3, "crown_width_over_height");  // lo > hi
  expect_habit_error(head + "crown_width_over_height = [0.6]\n", 3, "crown_width_over_height");
  expect_habit_error(head + "crown_width_over_height = 0.6\n", 3, "crown_width_over_height");
  expect_habit_error(head + "clear_bole_over_height = [0.1, 1.5]\n", 3, "clear_bole_over_height");
  expect_habit_error(head + "clear_bole_over_height = [\"a\", 0.5]\n", 3, "clear_bole_over_height");
  expect_habit_error(head + "trunk_fraction_min = -0.1\n", 3, "trunk_fraction_min");
  expect_habit_error(head + "single_leader = 1\n", 3, "single_leader");
  expect_habit_error(head + "lowest_leaf_over_height_min = 1.5\n", 3, "lowest_leaf_over_height_min");
  expect_habit_error(head + "crown_ratio = [0.1, 0.2]\n", 3, "crown_ratio");  // unknown key
  expect_habit_error("method = \"lsystem\"\nhabit = 3\n", 2, "habit");
  expect_habit_error("method = \"lsystem\"\n[habit]\n", 2, "habit");  // empty
}

TEST(HabitRanges, ChecksMetricsAgainstRanges) {
  HabitRanges r;
  r.crown_ratio = glm::dvec2(0.5, 1.0);
  r.trunk_fraction_min = 0.25;
  r.single_leader = true;
  r.lowest_leaf_min = 0.2;
  HabitMetrics m;
  m.crown_ratio = 1.2f;
  m.trunk_fraction = 0.3f;
  m.single_leader = false;
  m.lowest_leaf = 0.03f;  // foliage to the ground
  std::vector<HabitCheck> c = check_habit(m, r);
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c[0].key, "crown_width_over_height");
  EXPECT_FALSE(c[0].ok);
  EXPECT_EQ(c[0].range_text(), "0.50-1.00");
  EXPECT_TRUE(c[1].ok);
  EXPECT_EQ(c[1].range_text(), ">= 0.25");
  EXPECT_FALSE(c[2].ok);
  EXPECT_EQ(c[3].key, "lowest_leaf_over_height_min");
  EXPECT_FALSE(c[3].ok);
  EXPECT_EQ(c[3].range_text(), ">= 0.20");
}

// The registry takes the table (checked before the skeleton pass) and the method never sees
// it: the same preset with and without [habit] gives the same tree.
TEST(HabitRanges, RegistryAcceptsTheTableAndMethodsIgnoreIt) {
  const std::string base = default_species_text("lsystem");
  TreeModel a = generate_from_species_text(base, "fig2_1.toml");
  TreeModel b = generate_from_species_text(base + "\n[habit]\ncrown_width_over_height = [0.3, 0.6]\n", "fig2_1.toml");
  EXPECT_EQ(a.branches.indices.size(), b.branches.indices.size());
  EXPECT_EQ(a.leaves.size(), b.leaves.size());
  EXPECT_THROW(generate_from_species_text(base + "\n[habit]\ncrown_width_over_height = [0.6, 0.3]\n", "fig2_1.toml"),
               InputError);
}

// Every preset with a [habit] table is generated and measured against it: a preset that
// leaves its species' range fails here (README "Habit" table).
TEST(HabitRanges, PresetsMeasureInsideTheirRanges) {
  namespace fs = std::filesystem;
  size_t checked = 0;
  for (const auto& e : fs::directory_iterator(fs::path(FOREST_SOURCE_DIR) / "scenes" / "species")) {
    if (e.path().extension() != ".toml") continue;
    std::optional<HabitRanges> r = read_habit_ranges(TomlDocument::load(e.path()).root());
    if (!r) continue;
    TreeGraph graph;
    GenerateOptions options;
    options.skeleton = &graph;
    generate_from_species(e.path(), options);
    HabitMetrics m = measure_habit(graph);
    for (const HabitCheck& c : check_habit(m, *r))
      EXPECT_TRUE(c.ok) << e.path().stem().string() << ": " << c.key << " " << c.value << " outside " << c.range_text();
    ++checked;
  }
  EXPECT_GE(checked, 12u);  // the ten species and the two demo trees
}
