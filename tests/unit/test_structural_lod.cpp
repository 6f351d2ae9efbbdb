// Structural branch LOD (generators/mesh/structural_lod.h): whole chains removed by radius,
// fewer ring sides, a sloppy coarsest level; no back-to-back duplicates anywhere.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "generators/mesh/mesh_lod.h"
#include "generators/mesh/mesher.h"
#include "generators/mesh/structural_lod.h"
#include "generators/species/registry.h"
#include "gpu_types.h"

using namespace forest;
namespace fs = std::filesystem;

namespace {

fs::path species(const std::string& name) {
  return fs::path(FOREST_SOURCE_DIR) / "scenes" / "species" / (name + ".toml");
}

struct Generated {
  TreeModel model;
  TreeGraph graph;
};

Generated generate(const std::string& name) {
  Generated g;
  GenerateOptions options;
  options.skeleton = &g.graph;
  g.model = generate_from_species(species(name), options);
  return g;
}

size_t triangles(const Mesh& m) { return m.indices.size() / 3; }

}  // namespace

TEST(StructuralLod, BackToBackTrianglesAreFoundAndRemoved) {
  // A fin (two faces back to back), a same-winding copy, and an ordinary triangle.
  Mesh m;
  for (glm::vec3 p : {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)})
    m.vertices.push_back(Vertex{p});
  m.vertices.push_back(Vertex{glm::vec3(1, 0, 0)});  // a seam copy of vertex 1: same position
  m.indices = {0, 1, 2, /*fin*/ 0, 2, 4, /*copy*/ 2, 0, 1, /*other*/ 0, 1, 3};
  EXPECT_EQ(count_back_to_back(m), 3u);
  EXPECT_EQ(remove_back_to_back(m), 2u);  // the pair cancels; one of the two same-winding copies stays
  EXPECT_EQ(triangles(m), 2u);
  EXPECT_EQ(count_back_to_back(m), 0u);
}

TEST(StructuralLod, HeroesGetFiveLevelsDownToTwoPercentWithoutDuplicates) {
  for (const char* name : {"mig_a_hero", "mgv_n_hero", "particle_flow_oak_hero", "silhouettes_poplar_hero",
                           "visual_hull_ellipsoid_hero", "broadleaf", "fig2_1", "conifer"}) {
    SCOPED_TRACE(name);
    TreeModel m = generate_from_species(species(name));
    const size_t t0 = triangles(m.branches);
    std::printf("%s: LOD0 %zu", name, t0);
    float error = 0.0f;
    size_t previous = t0;
    for (const MeshLod& lod : m.branch_lods) {
      std::printf(" | %zu (%.1f %%, %.4f m)", triangles(lod.mesh), 100.0 * double(triangles(lod.mesh)) / double(t0),
                  double(lod.error));
      EXPECT_EQ(count_back_to_back(lod.mesh), 0u);
      EXPECT_GE(lod.error, error);
      EXPECT_GT(lod.error, 0.0f);
      EXPECT_LE(triangles(lod.mesh) * 10, previous * 9);
      error = lod.error;
      previous = triangles(lod.mesh);
    }
    std::printf("\n");
    EXPECT_EQ(count_back_to_back(m.branches), 0u);
    if (std::string(name).find("_hero") != std::string::npos) {
      EXPECT_GE(m.branch_lods.size(), 5u);
      ASSERT_FALSE(m.branch_lods.empty());
      EXPECT_LE(triangles(m.branch_lods.back().mesh) * 50, t0) << "coarsest above 2 % of LOD0";
    }
    EXPECT_LE(m.branch_lods.size() + 1, size_t(MAX_BRANCH_LODS));
  }
}

TEST(StructuralLod, LevelsRemoveWholeChainsThinnestFirst) {
  Generated g = generate("broadleaf");
  BranchMeshInfo info;
  Mesh lod0 = mesh_branches(g.graph, MesherParams{}, &info);
  const std::vector<LodChain> chains = lod_chains(g.graph, info);
  ASSERT_GT(chains.size(), 20u);
  // Keep the chains at least 2 cm thick at their base (and their parents): the pruned graph
  // holds exactly their nodes, and meshes to fewer triangles.
  std::vector<char> keep(chains.size(), 0);
  size_t kept_chains = 0;
  for (size_t c = 0; c < chains.size(); ++c) {
    bool parent_kept = chains[c].parent < 0 || keep[size_t(chains[c].parent)];
    keep[c] = parent_kept && (chains[c].parent < 0 || chains[c].base_radius >= 0.02f);
    kept_chains += keep[c];
  }
  ASSERT_LT(kept_chains, chains.size());
  TreeGraph pruned = prune_chains(g.graph, keep);
  EXPECT_LT(pruned.nodes.size(), g.graph.nodes.size());
  for (size_t n = 0; n < pruned.nodes.size(); ++n) {
    EXPECT_LT(pruned.nodes[n].parent, int32_t(n));
    if (pruned.nodes[n].parent >= 0) continue;
    EXPECT_EQ(n, 0u) << "one root";
  }
  // Every branch of the pruned tree starts at least 2 cm thick.
  BranchMeshInfo pruned_info;
  Mesh coarse = mesh_branches(pruned, MesherParams{}, &pruned_info);
  for (const LodChain& c : lod_chains(pruned, pruned_info))
    if (c.parent >= 0) EXPECT_GE(c.base_radius, 0.02f);
  EXPECT_LT(triangles(coarse), triangles(lod0));
  EXPECT_EQ(count_boundary_edges(coarse), count_boundary_edges(lod0)) << "closed but for the base ring";
}

TEST(StructuralLod, ErrorsAreMetres) {
  // The same skeleton twice as large: the same levels, errors twice as large.
  Generated g = generate("broadleaf");
  TreeGraph big = g.graph;
  for (TreeNode& n : big.nodes) n.position *= 2.0f, n.radius *= 2.0f;
  MesherParams p;
  BranchMeshInfo info, big_info;
  Mesh lod0 = mesh_branches(g.graph, p, &info);
  Mesh big0 = mesh_branches(big, p, &big_info);
  optimize_mesh(lod0);
  optimize_mesh(big0);
  auto small_lods = structural_lods(g.graph, p, lod0, info);
  auto big_lods = structural_lods(big, p, big0, big_info);
  ASSERT_EQ(small_lods.size(), big_lods.size());
  ASSERT_GE(small_lods.size(), 3u);
  for (size_t i = 0; i + 1 < small_lods.size(); ++i) {  // structural levels (the sloppy grid is not scale-free)
    EXPECT_EQ(triangles(small_lods[i].mesh), triangles(big_lods[i].mesh)) << "LOD" << i + 1;
    EXPECT_NEAR(big_lods[i].error, 2.0f * small_lods[i].error, 1e-3f * big_lods[i].error) << "LOD" << i + 1;
  }
  // Far below the tree's size; the sloppy level counts what it removed whole (its farthest
  // source vertex), still less than the tree.
  EXPECT_LT(small_lods[small_lods.size() - 2].error, 0.25f * g.model.bounding_sphere.w);
  EXPECT_GT(small_lods.back().error, small_lods[small_lods.size() - 2].error);
  EXPECT_LT(small_lods.back().error, g.model.bounding_sphere.w);
}
