// Branch mesh optimization and LOD chain (meshoptimizer), through build_tree_model.
#include <gtest/gtest.h>

#include <filesystem>

#include <meshoptimizer.h>

#include "generators/species/registry.h"
#include "generators/mesh/mesh_lod.h"
#include "generators/mesh/mesher.h"

using namespace forest;
namespace fs = std::filesystem;

namespace {

fs::path species(const char* name) {
  return fs::path(FOREST_SOURCE_DIR) / "scenes" / "species" / (std::string(name) + ".toml");
}

// Largest distance from a vertex of `a` to the nearest vertex of `b` (a cheap one-sided
// Hausdorff bound between two meshes of the same surface).
float vertex_distance(const Mesh& a, const Mesh& b) {
  float worst = 0.0f;
  for (const Vertex& v : a.vertices) {
    float best = 1e30f;
    for (const Vertex& w : b.vertices) best = std::min(best, glm::length(v.position - w.position));
    worst = std::max(worst, best);
  }
  return worst;
}

}  // namespace

TEST(Lod, ChainDecreasesInTrianglesWithNonDecreasingErrors) {
  for (const char* name : {"broadleaf", "conifer", "fig2_1"}) {
    TreeModel m = generate_from_species(species(name));
    ASSERT_GE(m.branch_lods.size(), 2u) << name;
    size_t previous = m.branches.indices.size() / 3;
    float error = 0.0f;
    for (size_t i = 0; i < m.branch_lods.size(); ++i) {
      const MeshLod& lod = m.branch_lods[i];
      size_t tris = lod.mesh.indices.size() / 3;
      EXPECT_LT(tris * 10, previous * 9 + 1) << name << " LOD" << i + 1;  // at least 10% fewer
      EXPECT_GE(lod.error, error) << name << " LOD" << i + 1;
      EXPECT_GT(lod.error, 0.0f);
      // Meters: far below the tree's size.
      EXPECT_LT(lod.error, 0.25f * m.bounding_sphere.w) << name;
      for (uint32_t idx : lod.mesh.indices) ASSERT_LT(idx, lod.mesh.vertices.size());
      // Only referenced vertices.
      std::vector<char> used(lod.mesh.vertices.size(), 0);
      for (uint32_t idx : lod.mesh.indices) used[idx] = 1;
      for (char u : used) EXPECT_TRUE(u);
      previous = tris;
      error = lod.error;
    }
    // The metadata lists them.
    ASSERT_EQ(m.meta["branch_lods"].size(), m.branch_lods.size());
    EXPECT_EQ(m.meta["branch_lods"][0]["level"], 1);
    EXPECT_EQ(m.meta["branch_lods"][0]["triangle_count"], m.branch_lods[0].mesh.indices.size() / 3);
  }
}

TEST(Lod, ErrorsAreInModelSpaceMeters) {
  TreeModel m = generate_from_species(species("broadleaf"));
  // The same tree twice as large: same triangle counts, errors twice as large.
  Mesh big = m.branches;
  for (Vertex& v : big.vertices) v.position *= 2.0f;
  static constexpr float kFractions[] = {0.5f, 0.25f, 0.12f};
  auto small_lods = simplify_lods(m.branches, kFractions);
  auto big_lods = simplify_lods(big, kFractions);
  ASSERT_EQ(small_lods.size(), big_lods.size());
  for (size_t i = 0; i < small_lods.size(); ++i) {
    EXPECT_EQ(small_lods[i].mesh.indices.size(), big_lods[i].mesh.indices.size());
    EXPECT_NEAR(big_lods[i].error, 2.0f * small_lods[i].error, 1e-3f * big_lods[i].error);
    // Every LOD vertex is an LOD0 vertex (edge collapses move nothing).
    EXPECT_EQ(vertex_distance(small_lods[i].mesh, m.branches), 0.0f);
  }
  // The errors bound how far LOD0 strays from the coarsest level, within a small factor
  // (the estimate is meshopt's, measured against the quadric of the original surface).
  const MeshLod& coarse = small_lods.back();
  EXPECT_GT(coarse.error, 0.0f);
  EXPECT_LT(coarse.error, 0.25f * m.bounding_sphere.w);
}

TEST(Lod, OptimizedForTheVertexCache) {
  TreeGraph g;
  TreeModel m = generate_from_species(species("conifer"));
  // Fewer vertex shader invocations than the mesher's raw order; same triangles as a set.
  Mesh raw = m.branches;  // already optimized by build_tree_model
  auto stats = meshopt_analyzeVertexCache(raw.indices.data(), raw.indices.size(), raw.vertices.size(), 16, 0, 0);
  EXPECT_LT(stats.acmr, 1.0f);  // < 1 vertex per triangle: good reuse
  auto fetch = meshopt_analyzeVertexFetch(raw.indices.data(), raw.indices.size(), raw.vertices.size(), sizeof(Vertex));
  EXPECT_LT(fetch.overfetch, 1.5f);
  // optimize_mesh keeps the surface: the same positions by triangle.
  Mesh before = m.branches;
  std::reverse(before.indices.begin(), before.indices.end());  // scramble (flips winding)
  for (size_t t = 0; t < before.indices.size(); t += 3) std::swap(before.indices[t], before.indices[t + 1]);
  Mesh after = before;
  optimize_mesh(after);
  EXPECT_EQ(after.indices.size(), before.indices.size());
  EXPECT_EQ(count_boundary_edges(after), count_boundary_edges(before));
  auto s2 = meshopt_analyzeVertexCache(after.indices.data(), after.indices.size(), after.vertices.size(), 16, 0, 0);
  auto s1 = meshopt_analyzeVertexCache(before.indices.data(), before.indices.size(), before.vertices.size(), 16, 0, 0);
  EXPECT_LE(s2.acmr, s1.acmr);
}
