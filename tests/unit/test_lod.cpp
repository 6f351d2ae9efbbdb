// Branch mesh optimization and LOD chain (meshoptimizer), through build_model.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <numeric>
#include <random>
#include <tuple>

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

// The triangles of a mesh as corner positions, each rotated to start at its smallest corner
// (winding kept), sorted: equal for two index/vertex orders of the same surface.
std::vector<std::array<float, 9>> triangle_set(const Mesh& mesh) {
  std::vector<std::array<float, 9>> out;
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    std::array<glm::vec3, 3> c;
    for (int k = 0; k < 3; ++k) c[size_t(k)] = mesh.vertices[mesh.indices[t + size_t(k)]].position;
    auto less = [](glm::vec3 a, glm::vec3 b) { return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z); };
    size_t first = less(c[1], c[0]) ? (less(c[2], c[1]) ? 2 : 1) : (less(c[2], c[0]) ? 2 : 0);
    std::array<float, 9> tri;
    for (size_t k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) tri[3 * k + size_t(a)] = c[(first + k) % 3][a];
    out.push_back(tri);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The same triangles (each with its winding) in a seeded random order.
std::vector<uint32_t> shuffled_triangles(const std::vector<uint32_t>& indices, uint32_t seed) {
  std::vector<size_t> order(indices.size() / 3);
  std::iota(order.begin(), order.end(), size_t(0));
  std::mt19937 rng(seed);
  for (size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[rng() % i]);
  std::vector<uint32_t> out;
  out.reserve(indices.size());
  for (size_t t : order) out.insert(out.end(), {indices[3 * t], indices[3 * t + 1], indices[3 * t + 2]});
  return out;
}

// The same mesh with its vertices in a seeded random order (indices remapped).
Mesh shuffled_vertices(const Mesh& mesh, uint32_t seed) {
  std::vector<uint32_t> where(mesh.vertices.size());
  std::iota(where.begin(), where.end(), 0u);
  std::mt19937 rng(seed);
  for (size_t i = where.size(); i > 1; --i) std::swap(where[i - 1], where[rng() % i]);
  Mesh out;
  out.vertices.resize(mesh.vertices.size());
  for (size_t i = 0; i < mesh.vertices.size(); ++i) out.vertices[where[i]] = mesh.vertices[i];
  for (uint32_t i : mesh.indices) out.indices.push_back(where[i]);
  return out;
}

// Bytes of vertex data fetched per byte of vertices used, through a 4 KiB FIFO cache of
// 64-byte lines (64 lines): the vertex fetch locality of an index order. 1 is ideal.
float small_cache_overfetch(const Mesh& mesh) {
  constexpr size_t kLine = 64, kLines = 64;
  std::vector<size_t> fifo(kLines, SIZE_MAX);
  size_t head = 0, fetched = 0;
  std::vector<char> used(mesh.vertices.size(), 0);
  for (uint32_t i : mesh.indices) {
    used[i] = 1;
    const size_t first = size_t(i) * sizeof(Vertex) / kLine, last = (size_t(i) * sizeof(Vertex) + sizeof(Vertex) - 1) / kLine;
    for (size_t line = first; line <= last; ++line) {
      if (std::find(fifo.begin(), fifo.end(), line) != fifo.end()) continue;
      fifo[head] = line, head = (head + 1) % kLines;
      fetched += kLine;
    }
  }
  const size_t bytes = size_t(std::count(used.begin(), used.end(), 1)) * sizeof(Vertex);
  return bytes ? float(double(fetched) / double(bytes)) : 0.0f;
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
  // The branch mesh exactly as build_model leaves it (mesh_branches, then optimize_mesh),
  // and the mesher's own output for the same skeleton (conifer meshes with the default ring
  // sides, 3..8) as the reference of what went in.
  TreeGraph g;
  GenerateOptions options;
  options.skeleton = &g;
  TreeModel m = generate_from_species(species("conifer"), options);
  const Mesh& out = m.branches;
  const Mesh raw = mesh_branches(g, MesherParams{});
  ASSERT_GE(out.indices.size() / 3, 1000u);
  // optimize_mesh keeps the surface: the same triangles (by corner positions, winding kept),
  // only reordered, and every vertex it keeps is used.
  ASSERT_EQ(out.indices.size(), raw.indices.size());
  EXPECT_EQ(triangle_set(out), triangle_set(raw)) << "the optimized mesh is not the mesher's surface";
  EXPECT_EQ(count_boundary_edges(out), count_boundary_edges(raw));
  {
    std::vector<char> used(out.vertices.size(), 0);
    for (uint32_t i : out.indices) {
      ASSERT_LT(i, out.vertices.size());
      used[i] = 1;
    }
    EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0) << "unreferenced vertices";
  }

  // Vertex cache (16-entry FIFO, meshopt's model): the order it has is as good as what
  // meshopt_optimizeVertexCache makes of this mesh (from the mesher's order or from a shuffled
  // one), and far better than the same triangles in a random order.
  const size_t nv = out.vertices.size();
  auto acmr = [](const std::vector<uint32_t>& idx, size_t vertices) {
    return meshopt_analyzeVertexCache(idx.data(), idx.size(), vertices, 16, 0, 0).acmr;
  };
  auto cache_optimized = [](const std::vector<uint32_t>& idx, size_t vertices) {
    std::vector<uint32_t> o(idx.size());
    meshopt_optimizeVertexCache(o.data(), idx.data(), idx.size(), vertices);
    return o;
  };
  const std::vector<uint32_t> shuffled = shuffled_triangles(out.indices, 12345);
  const float a_out = acmr(out.indices, nv);
  const float a_raw = acmr(raw.indices, raw.vertices.size());
  const float a_ref_raw = acmr(cache_optimized(raw.indices, raw.vertices.size()), raw.vertices.size());
  const float a_ref_shuffled = acmr(cache_optimized(shuffled, nv), nv);
  const float a_shuffled = acmr(shuffled, nv);
  std::printf("ACMR: built %.4f, mesher %.4f, meshopt(mesher) %.4f, meshopt(shuffled) %.4f, shuffled %.4f\n", a_out,
              a_raw, a_ref_raw, a_ref_shuffled, a_shuffled);
  EXPECT_LE(a_out, 1.01f * std::min(a_ref_raw, a_ref_shuffled)) << "not ordered for the vertex cache";
  EXPECT_GT(a_shuffled, 1.5f * a_out);
  EXPECT_LT(a_out, 1.0f);  // < 1 vertex shader invocation per triangle: good reuse

  // Vertex fetch: vertices sit in the order the triangles first use them (what
  // meshopt_optimizeVertexFetch does), so the overfetch is what it achieves, and far below a
  // random vertex order's.
  {
    std::vector<uint32_t> seen(nv, UINT32_MAX);
    uint32_t next = 0;
    size_t out_of_order = 0;
    for (uint32_t i : out.indices)
      if (seen[i] == UINT32_MAX) out_of_order += (i != next), seen[i] = next++;
    EXPECT_EQ(out_of_order, 0u) << "vertices are not in first-use order";
  }
  Mesh scattered = shuffled_vertices(out, 777);
  Mesh refetched = scattered;
  refetched.vertices.resize(
      meshopt_optimizeVertexFetch(refetched.vertices.data(), refetched.indices.data(), refetched.indices.size(),
                                  scattered.vertices.data(), scattered.vertices.size(), sizeof(Vertex)));
  // meshopt_analyzeVertexFetch models a 128 KiB cache, which holds this whole mesh: fine as an
  // upper bound, blind to the order. The small cache below is not.
  EXPECT_LT(meshopt_analyzeVertexFetch(out.indices.data(), out.indices.size(), nv, sizeof(Vertex)).overfetch, 1.05f);
  const float f_out = small_cache_overfetch(out), f_ref = small_cache_overfetch(refetched),
              f_scattered = small_cache_overfetch(scattered), f_raw = small_cache_overfetch(raw);
  std::printf("overfetch (4 KiB cache): built %.4f, mesher %.4f, meshopt %.4f, scattered %.4f\n", f_out, f_raw,
              f_ref, f_scattered);
  EXPECT_LE(f_out, 1.01f * f_ref) << "not ordered for vertex fetch";
  EXPECT_GT(f_scattered, 1.5f * f_out);
  EXPECT_LT(f_out, 1.5f);
}

TEST(Lod, TextureSeamsStayWhereLod0HasThem) {
  // Every LOD triangle's uv agree with its neighbours': no edge's uv are much longer than
  // the edge at the bark's scale (uv in tiles of bark_tile_meters). A triangle smeared across
  // the u seam, whose corners took u from both sides of it, spans the branch's whole
  // circumference in u: its edges reach (sides − 1) times their length.
  for (const char* name : {"broadleaf", "conifer", "quercus_robur"}) {
    TreeModel m = generate_from_species(species(name));
    ASSERT_GT(m.bark_tile_meters, 0.0f);
    ASSERT_FALSE(m.branch_lods.empty()) << name;
    for (size_t i = 0; i < m.branch_lods.size(); ++i) {
      const Mesh& mesh = m.branch_lods[i].mesh;
      float worst = 0.0f;
      for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
          const Vertex& a = mesh.vertices[mesh.indices[t + size_t(k)]];
          const Vertex& b = mesh.vertices[mesh.indices[t + size_t(k + 1) % 3]];
          worst = std::max(worst, glm::length(b.uv - a.uv) * m.bark_tile_meters /
                                      (glm::length(b.position - a.position) + 1e-6f));
        }
      std::printf("%s LOD%zu: %zu triangles, longest uv edge %.2f times its length\n", name, i + 1,
                  mesh.indices.size() / 3, worst);
      EXPECT_LT(worst, 3.0f) << name << " LOD" << i + 1;
    }
  }
}
