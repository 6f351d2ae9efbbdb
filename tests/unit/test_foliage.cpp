// The shared foliage stage (tree/foliage.h) and the foliage card (mesh/foliage_card.h).
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "generators/core/input_error.h"
#include "generators/core/toml_reader.h"
#include "generators/mesh/foliage_card.h"
#include "generators/methods/lsystem/lsystem.h"
#include "generators/species/registry.h"
#include "generators/tree/foliage.h"
#include "generators/tree/pipe_model.h"

using namespace forest;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A straight vertical branch of `segments` 1 m segments.
TreeGraph straight_branch(int segments) {
  TurtleParams p;
  p.step = 1.0f;
  TreeGraph g = interpret(std::string(size_t(segments), 'F'), p, 1);
  assign_pipe_radii(g, 0.01f, 2.0f);
  return g;
}

FoliageKeys plain_keys() {
  FoliageKeys k;
  k.leaf_size = 0.08f;
  k.shoot_length = 0.3f;
  k.size_jitter = 0.0f;
  k.spacing = 0.25f;
  k.depth = 2.0f;
  k.angle_deg = 60.0f;
  k.angle_jitter_deg = 0.0f;
  k.per_tip = 0;
  k.per_spray = 1;
  k.color_jitter = 0.0f;
  return k;
}

glm::vec3 axis_of(const LeafPlacement& l) { return l.rotation * glm::vec3(0, 1, 0); }

FoliageKeys keys_of(const std::string& text) {
  TomlDocument doc = TomlDocument::parse(text, "f.toml");
  return read_foliage_keys(doc.root(), LeafShape::ovate);
}

}  // namespace

TEST(Foliage, OnlyTheYoungWoodBearsFoliageAtTheSpacing) {
  TreeGraph g = straight_branch(4);
  place_foliage(g, plain_keys(), 3);
  // The top 2 m of a 4 m branch at one element per 0.25 m: 8 elements (the random offset
  // of the first lies in [0, 0.25)).
  EXPECT_GE(g.leaves.size(), 7u);
  EXPECT_LE(g.leaves.size(), 9u);
  for (const LeafPlacement& l : g.leaves) {
    EXPECT_GE(l.position.y, 2.0f - 1e-4f);
    EXPECT_NEAR(std::acos(axis_of(l).y) * 180.0 / kPi, 60.0, 1e-2);  // tilted by shoot_angle
    EXPECT_FLOAT_EQ(l.scale, 0.3f);                                  // element = the shoot
  }
  // Successive elements turn by the golden angle around the branch.
  for (size_t i = 1; i < g.leaves.size(); ++i) {
    glm::vec3 a = axis_of(g.leaves[i - 1]), b = axis_of(g.leaves[i]);
    double turn = std::acos(std::clamp(double(glm::dot(glm::normalize(glm::vec2(a.x, a.z)),
                                                        glm::normalize(glm::vec2(b.x, b.z)))),
                                       -1.0, 1.0));
    EXPECT_NEAR(turn, 2.399963229728653, 1e-3);
  }
  // Deeper foliage, denser spacing: proportionally more elements.
  FoliageKeys k = plain_keys();
  k.depth = 4.0f;
  k.spacing = 0.125f;
  TreeGraph dense = straight_branch(4);
  place_foliage(dense, k, 3);
  EXPECT_NEAR(double(dense.leaves.size()), 4.0 * double(g.leaves.size()), 4.0);
  // Single leaves: the element is the blade.
  k.shoot.single_leaf = true;
  place_foliage(dense, k, 3);
  EXPECT_FLOAT_EQ(dense.leaves[0].scale, 0.08f);
}

TEST(Foliage, TipsSpraysAndDeterminism) {
  FoliageKeys k = plain_keys();
  k.depth = 0.0f;  // no young wood: only the tip
  k.per_tip = 3;
  TreeGraph g = straight_branch(3);
  place_foliage(g, k, 5);
  ASSERT_EQ(g.leaves.size(), 3u);
  for (const LeafPlacement& l : g.leaves) EXPECT_NEAR(glm::distance(l.position, glm::vec3(0, 3, 0)), 0.0f, 1e-4f);
  // A spray of 4: each shoot grows from the end of the one before it.
  k.per_spray = 4;
  place_foliage(g, k, 5);
  ASSERT_EQ(g.leaves.size(), 12u);
  for (size_t i = 1; i < 4; ++i) {
    const LeafPlacement& prev = g.leaves[i - 1];
    glm::vec3 end = prev.position + axis_of(prev) * (0.8f * prev.scale);
    EXPECT_NEAR(glm::distance(g.leaves[i].position, end), 0.0f, 1e-4f);
  }
  TreeGraph again = straight_branch(3);
  place_foliage(again, k, 5);
  ASSERT_EQ(again.leaves.size(), g.leaves.size());
  for (size_t i = 0; i < g.leaves.size(); ++i) EXPECT_EQ(again.leaves[i].position, g.leaves[i].position);
  k.enabled = false;
  place_foliage(g, k, 5);
  EXPECT_TRUE(g.leaves.empty());
}

TEST(Foliage, UpperSidesFaceOutOfTheCrownAndColoursVary) {
  TurtleParams tp;
  tp.angle_deg = 35.0f;
  tp.roll_jitter_deg = 180.0f;
  tp.step = 0.5f;
  LSystem s{"X", {{'X', "F[+X][-X]FX", 1.0}}};
  TreeGraph g = interpret(rewrite(s, 4, 2), tp, 2);
  assign_pipe_radii(g, 0.01f, 2.0f);
  FoliageKeys k = plain_keys();
  k.color_jitter = 0.2f;
  k.per_tip = 2;
  place_foliage(g, k, 9);
  ASSERT_GT(g.leaves.size(), 50u);
  glm::vec3 centroid(0.0f);
  for (const LeafPlacement& l : g.leaves) centroid += l.position;
  centroid /= float(g.leaves.size());
  size_t outward = 0;
  std::set<float> reds;
  for (const LeafPlacement& l : g.leaves) {
    glm::vec3 n = l.rotation * glm::vec3(0, 0, 1);
    EXPECT_NEAR(glm::dot(n, axis_of(l)), 0.0f, 1e-5f);
    outward += glm::dot(n, l.position - centroid + glm::vec3(0, 1, 0)) > 0.0f;
    EXPECT_GE(l.color.g, 0.8f - 1e-5f);
    EXPECT_GE(l.color.r, l.color.b);
    reds.insert(l.color.r);
  }
  EXPECT_GT(outward, g.leaves.size() * 8 / 10);
  EXPECT_GT(reds.size(), g.leaves.size() / 2);
}

TEST(Foliage, KeysAndSeason) {
  FoliageKeys k = keys_of("leaf_size = 0.07\nshoot_length = 0.3\nleaves_per_shoot = 8\nleaf_phyllotaxis = \"opposite\"\n");
  EXPECT_FLOAT_EQ(k.leaf_size, 0.07f);
  EXPECT_EQ(k.shoot.leaves, 8);
  EXPECT_EQ(k.shoot.phyllotaxis, Phyllotaxis::opposite);
  EXPECT_NEAR(k.shoot.leaf_length, 0.07f / 0.3f, 1e-6f);
  EXPECT_FALSE(keys_of("leaf_size = 0\n").enabled);
  EXPECT_TRUE(keys_of("foliage = \"leaves\"\n").shoot.single_leaf);
  const glm::vec3 summer(0.1f, 0.3f, 0.05f), autumn(0.6f, 0.4f, 0.05f);
  FoliageKeys fall = keys_of("season = \"autumn\"\nautumn_color = [0.6, 0.4, 0.05]\n");
  EXPECT_EQ(season_leaf_color(fall, summer), autumn);
  EXPECT_EQ(season_leaf_color(keys_of("autumn_color = [0.6, 0.4, 0.05]\n"), summer), summer);
  EXPECT_EQ(season_leaf_color(keys_of("season = \"autumn\"\nevergreen = true\n"), summer), summer);
  for (const char* bad : {"leaf_size = 0.3\nshoot_length = 0.3\n", "foliage = \"fronds\"\n",
                          "leaves_per_shoot = 2\n", "season = \"spring\"\n", "shoot_spacing = nan\n",
                          "leaf_phyllotaxis = \"random\"\n", "shoots_per_spray = 9\n"}) {
    try {
      keys_of(bad);
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      std::string key = std::string(bad).substr(0, std::string(bad).find(' '));
      if (std::string(bad).find("shoot_length = 0.3") != std::string::npos) key = "leaf_size";
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
}

TEST(Foliage, EveryMethodGetsTheSharedFoliage) {
  // One lsystem and one graph method, both foliated by the shared keys.
  for (const std::string method : {"lsystem", "mgv"}) {
    std::string text = default_species_text(method);
    TreeModel m = generate_from_species_text(text, method + ".toml");
    ASSERT_GT(m.leaves.size(), 100u) << method;
    EXPECT_EQ(m.meta["foliage"]["element"], method == "lsystem" ? "leaf" : "shoot");  // fig2_1: single leaves
    // In autumn the leaf material changes, the skeleton and placement do not.
    std::string fall = text;
    fall.insert(fall.find('\n') + 1, "season = \"autumn\"\n");
    TreeModel f = generate_from_species_text(fall, method + ".toml");
    EXPECT_EQ(f.leaf_color, glm::vec3(0.55f, 0.34f, 0.05f));  // the presets' autumn_color
    EXPECT_NE(m.leaf_color, f.leaf_color);
    ASSERT_EQ(f.leaves.size(), m.leaves.size());
    EXPECT_EQ(f.leaves[7].position, m.leaves[7].position);
  }
  // An L-system's 'L' symbols place the elements themselves; the foliage stage sizes them.
  const std::string with_l = "method = \"lsystem\"\niterations = 2\naxiom = \"X\"\nshoot_length = 0.4\n"
                             "leaf_size_jitter = 0\n[[production]]\npredecessor = \"X\"\nsuccessor = \"F[+XL]F[-XL]XL\"\n";
  TreeModel l = generate_from_species_text(with_l, "l.toml");
  ASSERT_GT(l.leaves.size(), 0u);
  for (const LeafPlacement& leaf : l.leaves) EXPECT_FLOAT_EQ(leaf.scale, 0.4f);
}

TEST(FoliageCard, ShootTextureIsTheLeafModelInThePhyllotaxis) {
  ShootDesign d;
  d.leaves = 7;
  d.leaf_length = 0.3f;
  d.phyllotaxis = Phyllotaxis::alternate;
  std::vector<ShootLeaf> alt = shoot_leaves(d);
  ASSERT_EQ(alt.size(), 7u);
  // Alternate: lateral leaves change sides, one per node.
  for (size_t i = 2; i < alt.size(); ++i) {
    EXPECT_LT(alt[i].direction.x * alt[i - 1].direction.x, 0.0f) << i;
    EXPECT_GT(alt[i].base.y, alt[i - 1].base.y);
  }
  d.phyllotaxis = Phyllotaxis::opposite;
  std::vector<ShootLeaf> opp = shoot_leaves(d);
  for (size_t i = 1; i + 1 < opp.size(); i += 2) {  // pairs at one node, on both sides
    EXPECT_FLOAT_EQ(opp[i].base.y, opp[i + 1].base.y);
    EXPECT_LT(opp[i].direction.x * opp[i + 1].direction.x, 0.0f);
  }
  // The card holds every leaf: the texture's coverage grows with the leaves on it and the
  // texture is deterministic.
  auto coverage = [](const Image8& t) {
    double a = 0.0;
    for (size_t i = 3; i < t.rgba.size(); i += 4) a += t.rgba[i] / 255.0;
    return a / double(t.width * t.height);
  };
  ShootDesign few = d, many = d;
  few.leaves = 4;
  many.leaves = 12;
  Image8 t4 = make_foliage_texture(few, 128), t12 = make_foliage_texture(many, 128);
  EXPECT_GT(coverage(t12), 1.3 * coverage(t4) * foliage_card_aspect(few) / foliage_card_aspect(many));
  EXPECT_EQ(make_foliage_texture(many, 128).rgba, t12.rgba);
  // The border is clear (nothing cut off by the card's edge).
  for (uint32_t x = 0; x < 128; ++x) {
    EXPECT_EQ(t12.rgba[x * 4 + 3], 0) << x;
    EXPECT_EQ(t12.rgba[(x * 128) * 4 + 3], 0) << x;
    EXPECT_EQ(t12.rgba[(x * 128 + 127) * 4 + 3], 0) << x;
  }
  // A single-leaf design is the leaf card and texture.
  ShootDesign single;
  single.single_leaf = true;
  EXPECT_EQ(foliage_card_aspect(single), leaf_card_aspect(LeafShape::ovate));
  EXPECT_EQ(make_foliage_texture(single, 64).rgba, make_leaf_texture(LeafShape::ovate, 64).rgba);
}

TEST(Foliage, NothingReachesTheGround) {
  // A 1 m stem bearing foliage along all of it: the elements of its lowest 0.3 m, and those
  // whose tip would dip below that, are not placed; the rest are.
  TreeGraph g = straight_branch(1);
  FoliageKeys k = plain_keys();
  k.spacing = 0.05f;
  k.angle_deg = 120.0f;  // pointing down and out
  place_foliage(g, k, 5);
  ASSERT_GE(g.leaves.size(), 4u);
  for (const LeafPlacement& l : g.leaves) {
    EXPECT_GE(l.position.y, kFoliageGroundClearance - 1e-5f);
    EXPECT_GE((l.position + axis_of(l) * l.scale).y, kFoliageGroundClearance - 1e-5f);
  }
}
