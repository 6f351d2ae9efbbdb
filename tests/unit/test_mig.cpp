// Method `mig` (Xu 2015 ch4): iterated graphs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "generators/asset/asset_io.h"
#include "generators/core/input_error.h"
#include "generators/methods/common/graph_skeleton.h"
#include "generators/methods/common/graph_volume.h"
#include "generators/species/registry.h"
#include "generators/methods/mig/mig_method.h"

using namespace forest;
namespace fs = std::filesystem;

namespace {

fs::path species(const std::string& name) {
  return fs::path(FOREST_SOURCE_DIR) / "scenes" / "species" / (name + ".toml");
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

MigParams small_params() {
  MigParams P;
  Shape trunk;
  trunk.kind = ShapeKind::Cylinder;
  trunk.radius = 0.4f;
  trunk.height = 3.0f;
  trunk.endpoints = false;
  Shape crown;
  crown.kind = ShapeKind::SpherePortion;
  crown.center = glm::vec3(0, 2.5f, 0);
  crown.radius = 3.0f;
  crown.angle = 0.4f * 3.14159265f;
  P.volume = {trunk, crown};
  P.nodes = 1500;
  P.shell = 0.8f;
  P.subgraph_nodes = 60;
  P.subgraph_radius = 1.5f;
  P.shrink = 0.7f;
  MigLevel l1;
  l1.branching = 8;
  MigLevel l2;
  l2.branching = 3;
  l2.alpha = 0.3f * 3.14159265f;
  P.levels = {l1, l2, l2};
  return P;
}

}  // namespace

TEST(Mig, LevelsMultiplyEndpointsAndStayInTheirVolumes) {
  MigParams P = small_params();
  MigStats st;
  TreeGraph tree = grow_mig(P, 5, &st);
  EXPECT_EQ(st.subgraphs, 8u + 8u * 3u);
  EXPECT_EQ(st.endpoints, 8u + 24u + 72u);
  EXPECT_EQ(st.unreachable, 0u);  // 4-spacing Yao graphs on Poisson nodes: all reached here
  // Every final-level endpoint is a tip (no subgraph grew from it), every earlier one is not.
  // An endpoint may fall on another endpoint's path (then it is no tip).
  EXPECT_LE(count_tips(tree), 72u);
  EXPECT_GE(count_tips(tree), 50u);
  std::vector<char> has_child(tree.nodes.size(), 0);
  for (size_t i = 1; i < tree.nodes.size(); ++i) {
    ASSERT_LT(size_t(tree.nodes[i].parent), i);
    has_child[size_t(tree.nodes[i].parent)] = 1;
  }
  // Level-1 nodes lie in the user's volume; level ℓ nodes within the subgraph sphere of
  // the level: the distance to their nearest level ℓ−1 node is at most r_ℓ.
  float r = P.subgraph_radius;
  for (uint32_t level = 0; level < 3; ++level) {
    for (size_t i = 1; i < tree.nodes.size(); ++i) {
      const TreeNode& n = tree.nodes[i];
      if (n.order != level) continue;
      if (level == 0) {
        EXPECT_TRUE(volume_contains(P.volume, n.position)) << i;
        continue;
      }
      // Walk up to the subgraph root (first ancestor of a lower level).
      size_t a = size_t(n.parent);
      while (tree.nodes[a].order == level) a = size_t(tree.nodes[a].parent);
      EXPECT_LE(glm::length(n.position - tree.nodes[a].position), r + 1e-4f) << i;
    }
    if (level > 0) r *= P.shrink;
  }
}

TEST(Mig, LevelOneEndpointsLieInTheSurfaceShell) {
  MigParams P = small_params();
  P.levels.resize(1);
  TreeGraph tree = grow_mig(P, 6);
  std::vector<Shape> crown{P.volume[1]};
  auto children = children_of(tree);
  size_t tips = 0;
  for (size_t i = 1; i < tree.nodes.size(); ++i)
    if (children[i].empty()) {
      ++tips;
      EXPECT_TRUE(in_surface_shell(crown, tree.nodes[i].position, P.shell)) << i;
    }
  EXPECT_LE(tips, 8u);
  EXPECT_GE(tips, 5u);
}

TEST(Mig, DownwardDirectionHangsSubgraphs) {
  MigParams P = small_params();
  P.levels[1].direction = glm::vec3(0, -1, 0);
  P.levels.resize(2);
  TreeGraph tree = grow_mig(P, 8);
  for (size_t i = 1; i < tree.nodes.size(); ++i) {
    if (tree.nodes[i].order != 1) continue;
    size_t a = size_t(tree.nodes[i].parent);
    while (tree.nodes[a].order == 1) a = size_t(tree.nodes[a].parent);
    glm::vec3 d = tree.nodes[i].position - tree.nodes[a].position;
    // Inside a cone of half-angle 0.3π around straight down.
    EXPECT_LE(d.y, -std::cos(0.3f * 3.14159265f) * glm::length(d) + 1e-4f);
  }
}

TEST(Mig, DefaultPresetIsTheFileAndDeterministic) {
  EXPECT_EQ(default_species_text("mig"), read_text(species("mig_o")));
  auto bytes = [&](uint64_t seed) {
    return encode_glb(generate_from_species_text(default_species_text("mig"), "mig_o.toml", {seed}));
  };
  EXPECT_EQ(bytes(2), bytes(2));
  EXPECT_NE(bytes(2), bytes(3));
}

TEST(Mig, ForestPresetsFitTheBudget) {
  for (const char* name : {"mig_o", "mig_j"}) {
    TreeModel m = generate_from_species(species(name));
    EXPECT_LE(m.branches.indices.size() / 3, 6500u) << name;
    EXPECT_LE(m.leaves.size(), 12000u) << name;  // shoot cards; method demos have no floor
    EXPECT_GE(m.leaves.size(), 300u) << name;
    EXPECT_GE(double(m.meta["height"]), 5.0) << name;
  }
}

TEST(Mig, ErrorsNameTheKey) {
  auto expect_key = [&](const std::string& text, const std::string& key) {
    try {
      generate_from_species_text(text, "t.toml");
      ADD_FAILURE() << "no error for " << key;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  std::string base = default_species_text("mig");
  expect_key("method = \"mig\"\n[[level]]\nb = 3\n", "volume");
  expect_key("method = \"mig\"\n[[volume]]\nshape = \"sphere\"\n", "level");
  expect_key("method = \"mig\"\n[[volume]]\nshape = \"blob\"\n[[level]]\nb = 3\n", "shape");
  expect_key("method = \"mig\"\n[[volume]]\nradius = -1.0\n[[level]]\nb = 3\n", "radius");
  // Runaway recursion is refused before it runs.
  expect_key("method = \"mig\"\n[[volume]]\nshape = \"sphere\"\n[[level]]\nb = 100\n[[level]]\nb = 100\n"
             "[[level]]\nb = 100\n",
             "level");
  std::string t = base;
  t.replace(t.find("shrink = 0.6"), 12, "shrink = inf");
  expect_key(t, "shrink");
}

TEST(Mig, TrunkHeightIsAStraightClearBole) {
  // The trunk: the first nodes, straight up from the root (each the parent of the next).
  auto trunk_of = [](const TreeGraph& t, glm::vec3 root) {
    size_t m = 1;
    while (m < t.nodes.size() && t.nodes[m].parent == int32_t(m - 1) && t.nodes[m].position.x == root.x &&
           t.nodes[m].position.z == root.z)
      ++m;
    return m;
  };
  // Trunk nodes below its top that fork (have a child besides the next trunk node).
  auto side_branches = [&](const TreeGraph& t, glm::vec3 root) {
    size_t m = trunk_of(t, root);
    std::vector<int> children(t.nodes.size(), 0);
    for (size_t i = 1; i < t.nodes.size(); ++i) ++children[size_t(t.nodes[i].parent)];
    int n = 0;
    for (size_t i = 0; i + 1 < m; ++i) n += children[i] > 1;
    return n;
  };
  MigParams P = small_params();
  P.trunk_height = 2.0f;
  TreeGraph top = grow_mig(P, 4, nullptr);
  size_t m = trunk_of(top, P.root);
  EXPECT_NEAR(top.nodes[m - 1].position.y - P.root.y, 2.0f, 1e-4f);
  EXPECT_EQ(side_branches(top, P.root), 0);
  // Excurrent: branches leave anywhere along it (a trunk into the crown, which starts low).
  P.trunk_height = 5.2f;
  TreeGraph high = grow_mig(P, 4, nullptr);
  P.trunk_sources_all = true;
  TreeGraph all = grow_mig(P, 4, nullptr);
  EXPECT_EQ(side_branches(high, P.root), 0);
  EXPECT_GT(side_branches(all, P.root), 0);
}
