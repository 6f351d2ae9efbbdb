// The least-cost-path substrate (Yao-8 graph, Dijkstra) and method `mgv` (Xu 2015 ch5).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "generators/asset/asset_io.h"
#include "generators/core/input_error.h"
#include "generators/core/rng.h"
#include "generators/methods/common/graph_dijkstra.h"
#include "generators/methods/common/graph_poisson.h"
#include "generators/methods/common/graph_skeleton.h"
#include "generators/methods/common/graph_yao.h"
#include "generators/species/registry.h"
#include "generators/methods/mgv/mgv_grow.h"
#include "generators/methods/mgv/mgv_method.h"

using namespace forest;
namespace fs = std::filesystem;

namespace {

std::vector<glm::vec3> random_points(size_t n, uint64_t seed) {
  Rng rng(seed);
  Box box{glm::vec3(0.0f), glm::vec3(4.0f)};
  return poisson_disc([](glm::vec3) { return true; }, box, n, 0.15f, rng, 100000);
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path species(const std::string& name) {
  return fs::path(FOREST_SOURCE_DIR) / "scenes" / "species" / (name + ".toml");
}

}  // namespace

TEST(GraphYao, DegreeAtMostEightAndNearestInEachOctant) {
  std::vector<glm::vec3> pts = random_points(400, 3);
  ASSERT_GT(pts.size(), 300u);
  YaoGraph g = build_yao8(pts, 1e6f);
  for (uint32_t u = 0; u < g.size(); ++u) {
    ASSERT_LE(g.offsets[u + 1] - g.offsets[u], 8u);
    // Brute force: nearest in every octant (ties to the smaller index).
    int32_t best[8];
    float best_d[8];
    for (int k = 0; k < 8; ++k) best[k] = -1, best_d[k] = std::numeric_limits<float>::max();
    for (uint32_t v = 0; v < g.size(); ++v) {
      if (v == u) continue;
      glm::vec3 d = pts[v] - pts[u];
      float d2 = glm::dot(d, d);
      int s = yao_sector(d);
      if (d2 < best_d[s]) best_d[s] = d2, best[s] = int32_t(v);
    }
    int expected = 0;
    for (int k = 0; k < 8; ++k) expected += best[k] >= 0;
    ASSERT_EQ(int(g.offsets[u + 1] - g.offsets[u]), expected) << u;
    for (uint32_t e = g.offsets[u]; e < g.offsets[u + 1]; ++e) {
      int s = yao_sector(pts[g.targets[e]] - pts[u]);
      EXPECT_EQ(int32_t(g.targets[e]), best[s]) << "node " << u << " octant " << s;
      EXPECT_NEAR(g.lengths[e], glm::length(pts[g.targets[e]] - pts[u]), 1e-5f);
    }
  }
}

TEST(GraphPoisson, MinimumDistanceAndInsideVolume) {
  Shape sphere;
  sphere.radius = 2.0f;
  Rng rng(9);
  auto pts = poisson_disc([&](glm::vec3 p) { return shape_contains(sphere, p); }, shape_bounds(sphere),
                          800, 0.2f, rng, 200000);
  EXPECT_EQ(pts.size(), 800u);
  for (size_t i = 0; i < pts.size(); ++i) {
    EXPECT_LE(glm::length(pts[i]), 2.0f);
    for (size_t j = 0; j < i; ++j) ASSERT_GE(glm::length(pts[i] - pts[j]), 0.2f);
  }
}

TEST(GraphDijkstra, OptimalAgainstBellmanFord) {
  std::vector<glm::vec3> pts = random_points(150, 5);
  YaoGraph g = build_yao8(pts, 1.0f);
  // Arbitrary non-negative weights: lengths scaled by a per-edge random factor.
  std::vector<float> w(g.targets.size());
  Rng rng(17);
  for (float& x : w) x = float(rng.uniform(0.0, 3.0));
  std::vector<uint32_t> sources{0, 7};
  ShortestPaths sp = dijkstra(
      g, sources, [&](uint32_t, uint32_t e) { return w[e]; }, [](uint32_t, int32_t, const ShortestPaths&) {});
  // Bellman–Ford.
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> bf(g.size(), inf);
  for (uint32_t s : sources) bf[s] = 0.0;
  for (size_t round = 0; round < g.size(); ++round) {
    bool changed = false;
    for (uint32_t u = 0; u < g.size(); ++u)
      for (uint32_t e = g.offsets[u]; e < g.offsets[u + 1]; ++e)
        if (bf[u] + w[e] < bf[g.targets[e]] - 1e-12) bf[g.targets[e]] = bf[u] + w[e], changed = true;
    if (!changed) break;
  }
  size_t reached = 0, tree_edges = 0;
  for (uint32_t v = 0; v < g.size(); ++v) {
    if (std::isinf(bf[v])) {
      EXPECT_FALSE(sp.reached(v));
      continue;
    }
    ++reached;
    EXPECT_NEAR(sp.dist[v], bf[v], 1e-9) << v;
    if (sp.parent[v] >= 0) {
      ++tree_edges;
      // Equality on parent edges.
      uint32_t u = uint32_t(sp.parent[v]);
      double we = inf;
      for (uint32_t e = g.offsets[u]; e < g.offsets[u + 1]; ++e)
        if (g.targets[e] == v) we = std::min(we, double(w[e]));
      EXPECT_NEAR(sp.dist[v], sp.dist[u] + we, 1e-9);
      EXPECT_EQ(sp.hops[v], sp.hops[u] + 1);
    }
  }
  // Parent pointers form a forest with one tree per source: |E| = |V| − #sources.
  EXPECT_EQ(tree_edges, reached - sources.size());
  // dist[v] <= dist[u] + w(u, v) on every edge.
  for (uint32_t u = 0; u < g.size(); ++u)
    for (uint32_t e = g.offsets[u]; e < g.offsets[u + 1]; ++e)
      if (sp.reached(u)) EXPECT_LE(sp.dist[g.targets[e]], sp.dist[u] + w[e] + 1e-9);
}

TEST(Mgv, GuidedWeightsStayInZeroToTwoD) {
  std::vector<glm::vec3> pts = random_points(200, 8);
  YaoGraph g = build_yao8(pts, 1.0f);
  Rng rng(4);
  for (uint32_t u = 0; u < g.size(); ++u) {
    glm::vec3 v(float(rng.symmetric()), float(rng.symmetric()), float(rng.symmetric()));
    v = glm::normalize(v + glm::vec3(0, 0, 1e-3f));
    for (uint32_t e = g.offsets[u]; e < g.offsets[u + 1]; ++e) {
      glm::vec3 dir = glm::normalize(pts[g.targets[e]] - pts[u]);
      float w = guided_weight(g.lengths[e], dir, v);
      EXPECT_GE(w, -1e-6f);
      EXPECT_LE(w, 2.0f * g.lengths[e] + 1e-6f);
    }
  }
  glm::vec3 up(0, 1, 0);
  EXPECT_NEAR(guided_weight(2.0f, up, up), 0.0f, 1e-6f);   // along the vector: free
  EXPECT_NEAR(guided_weight(2.0f, -up, up), 4.0f, 1e-6f);  // against it: 2d
}

TEST(Mgv, GuideRotatesByAlphaAboutUpCrossG) {
  const float deg = 3.14159265f / 180.0f;
  glm::vec3 g = glm::normalize(glm::vec3(0.3f, 0.8f, -0.2f));
  for (float a : {4.0f, 30.0f, -10.0f, 90.0f}) {
    glm::vec3 r = rotate_guide(g, glm::vec3(1, 0, 0), a * deg);
    EXPECT_NEAR(glm::length(r), 1.0f, 1e-5f);
    EXPECT_NEAR(std::acos(std::clamp(glm::dot(r, g), -1.0f, 1.0f)), std::abs(a) * deg, 1e-3f) << a;
    // The axis is horizontal: rotation stays in the vertical plane through g.
    EXPECT_NEAR(glm::dot(r, glm::normalize(glm::cross(glm::vec3(0, 1, 0), g))), 0.0f, 1e-5f);
    // Positive alpha bends away from up.
    if (a > 0) EXPECT_LT(r.y, g.y);
  }
  // Vertical parent vector: rotates toward the edge direction.
  glm::vec3 r = rotate_guide(glm::vec3(0, 1, 0), glm::vec3(0, 0, 1), 30.0f * deg);
  EXPECT_NEAR(r.z, 0.5f, 1e-5f);
  EXPECT_EQ(rotate_guide(g, glm::vec3(1, 0, 0), 0.0f), g);
}

namespace {
MgvParams small_params(float alpha_deg) {
  MgvParams P;
  P.size = glm::vec3(6, 8, 6);
  P.nodes = 6000;
  MgvIteration trunk;
  trunk.select = EndpointSelect::Point;
  trunk.point = glm::vec3(0, 3, 0);
  MgvIteration crown;
  crown.select = EndpointSelect::Volume;
  crown.endpoints = 20;
  crown.alpha1 = crown.alpha2 = alpha_deg * 3.14159265f / 180.0f;
  Shape e;
  e.kind = ShapeKind::HalfEllipsoid;
  e.center = glm::vec3(0, 3, 0);
  e.radii = glm::vec3(2.5f, 4.5f, 2.5f);
  crown.volume.push_back(e);
  MgvIteration later;
  later.endpoints = 40;
  later.hops = 3;
  later.alpha1 = 30.0f * 3.14159265f / 180.0f;
  P.iterations = {trunk, crown, later};
  return P;
}
}  // namespace

TEST(Mgv, ZeroAlphaKeepsEveryGuideVertical) {
  MgvParams P = small_params(0.0f);
  P.iterations.pop_back();
  MgvGraph g = build_mgv_graph(P, 1);
  MgvStats st;
  TreeGraph tree = grow_mgv(g, P, 1, &st);
  ASSERT_GT(tree.nodes.size(), 10u);
  size_t set = 0;
  for (glm::vec3 v : st.guides) {
    if (v == glm::vec3(0.0f)) continue;
    ++set;
    EXPECT_NEAR(v.y, 1.0f, 1e-6f);
  }
  EXPECT_GT(set, g.graph.size() / 2);
}

TEST(Mgv, TreeIsOneTreeWithEndpointsAndRadiiGrowTowardRoot) {
  MgvParams P = small_params(6.0f);
  MgvGraph g = build_mgv_graph(P, 2);
  MgvStats st;
  TreeGraph tree = grow_mgv(g, P, 2, &st);
  ASSERT_EQ(st.endpoints_per_iteration.size(), 3u);
  EXPECT_EQ(st.endpoints_per_iteration[0], 1u);
  EXPECT_EQ(st.endpoints_per_iteration[1], 20u);
  EXPECT_EQ(st.endpoints_per_iteration[2], 40u);
  // One branch per endpoint; an endpoint may fall on another's path and then is no tip.
  EXPECT_LE(count_tips(tree), st.endpoints);
  EXPECT_GE(count_tips(tree), st.endpoints * 2 / 3);
  for (size_t i = 1; i < tree.nodes.size(); ++i) {
    ASSERT_GE(tree.nodes[i].parent, 0);
    ASSERT_LT(size_t(tree.nodes[i].parent), i);
  }
  // Guides of tree nodes are unit vectors.
  for (size_t v = 0; v < st.tree_node.size(); ++v)
    if (st.tree_node[v] >= 0) EXPECT_NEAR(glm::length(st.guides[v]), 1.0f, 1e-4f);
  assign_length_radii(tree, 0.01f, 0.3f, 0.3f);
  for (size_t i = 1; i < tree.nodes.size(); ++i)
    EXPECT_GT(tree.nodes[size_t(tree.nodes[i].parent)].radius, tree.nodes[i].radius) << i;
  EXPECT_FLOAT_EQ(tree.nodes[0].radius, 0.3f);
}

TEST(Mgv, HangingPolicyPicksEndpointsBelowTheirSource) {
  MgvParams P = small_params(6.0f);
  P.iterations[2].policy = EndpointPolicy::Hanging;
  P.iterations[2].hops = 4;
  MgvGraph g = build_mgv_graph(P, 3);
  TreeGraph tree = grow_mgv(g, P, 3);
  // Every tip of the last iteration lies below the node its branch starts from.
  auto children = children_of(tree);
  size_t checked = 0;
  for (size_t i = 1; i < tree.nodes.size(); ++i) {
    if (!children[i].empty() || tree.nodes[i].order != 2) continue;
    size_t s = i;
    while (tree.nodes[s].order == 2) s = size_t(tree.nodes[s].parent);
    EXPECT_LT(tree.nodes[i].position.y, tree.nodes[s].position.y);
    ++checked;
  }
  EXPECT_GT(checked, 0u);
}

TEST(Mgv, DefaultPresetIsTheFileAndDeterministic) {
  EXPECT_EQ(default_species_text("mgv"), read_text(species("mgv_c")));
  auto bytes = [&](uint64_t seed) {
    return encode_glb(generate_from_species_text(default_species_text("mgv"), "mgv_c.toml", {seed}));
  };
  EXPECT_EQ(bytes(4), bytes(4));
  EXPECT_NE(bytes(4), bytes(5));
}

TEST(Mgv, ForestPresetsFitTheBudget) {
  for (const char* name : {"mgv_c", "mgv_o"}) {
    TreeModel m = generate_from_species(species(name));
    EXPECT_LE(m.branches.indices.size() / 3, 6500u) << name;
    EXPECT_LE(m.leaves.size(), 12000u) << name;  // shoot cards; method demos have no floor
    EXPECT_GE(m.leaves.size(), 300u) << name;
    EXPECT_GE(double(m.meta["height"]), 5.0) << name;
  }
}

TEST(Mgv, ErrorsNameTheKey) {
  std::string base = default_species_text("mgv");
  auto expect_key = [&](const std::string& text, const std::string& key) {
    try {
      generate_from_species_text(text, "t.toml");
      ADD_FAILURE() << "no error for " << key;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  std::string t = base;
  t.replace(t.find("nodes = 30000"), 13, "nodes = 99999999");
  expect_key(t, "nodes");
  t = base;
  t.replace(t.find("hops = 6"), 8, "hops = nan");
  expect_key(t, "hops");
  t = base;
  t.replace(t.find("outer = 0.6"), 11, "outer = 0.0");
  expect_key(t, "outer");
  expect_key("method = \"mgv\"\nnodes = 1000\n", "iteration");
}

TEST(Mgv, SourcesAboveKeepsTheBoleClear) {
  // Forks of the tree below `height` (m above the root): none when every iteration after
  // the trunk takes its sources from above 2.5 m; some without the key.
  auto forks_below = [](const TreeGraph& t, float height) {
    std::vector<int> children(t.nodes.size(), 0);
    for (size_t i = 1; i < t.nodes.size(); ++i) ++children[size_t(t.nodes[i].parent)];
    int n = 0;
    for (size_t i = 0; i < t.nodes.size(); ++i)
      if (children[i] > 1 && t.nodes[i].position.y - t.nodes[0].position.y < height) ++n;
    return n;
  };
  MgvParams P = small_params(6.0f);
  P.iterations[1].volume[0].center.y = 2.0f;  // a crown reaching down beside the trunk
  MgvGraph g = build_mgv_graph(P, 2);
  TreeGraph plain = grow_mgv(g, P, 2, nullptr);
  P.iterations[1].sources_above = P.iterations[2].sources_above = 2.5f;
  TreeGraph clear = grow_mgv(g, P, 2, nullptr);
  EXPECT_GT(forks_below(plain, 2.4f), 0);
  EXPECT_EQ(forks_below(clear, 2.4f), 0);
  EXPECT_GT(clear.nodes.size(), 50u);
}
