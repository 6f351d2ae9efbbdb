// Bifurcations: the enclosing sphere of two branches, the junction that joins cut rings, and
// a branch mesh without holes at forks.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "generators/species/registry.h"
#include "generators/tree/allometry.h"
#include "generators/mesh/frames.h"
#include "generators/mesh/junction.h"
#include "generators/methods/lsystem/lsystem.h"
#include "generators/mesh/mesher.h"
#include "generators/tree/pipe_model.h"

using namespace forest;
namespace fs = std::filesystem;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Directed-edge census of a mesh after welding equal positions.
struct EdgeCensus {
  size_t boundary = 0;       // undirected edges used once
  size_t non_manifold = 0;   // used three or more times
  size_t inconsistent = 0;   // used twice in the same direction (a flipped triangle)
};

EdgeCensus census(const Mesh& m) {
  std::map<std::array<float, 3>, uint32_t> ids;
  std::vector<uint32_t> weld(m.vertices.size());
  for (size_t i = 0; i < m.vertices.size(); ++i) {
    const glm::vec3& p = m.vertices[i].position;
    weld[i] = ids.emplace(std::array<float, 3>{p.x, p.y, p.z}, uint32_t(ids.size())).first->second;
  }
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (size_t t = 0; t < m.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) directed[{weld[m.indices[t + k]], weld[m.indices[t + (k + 1) % 3]]}]++;
  EdgeCensus c;
  for (const auto& [e, n] : directed) {
    auto rev = directed.find({e.second, e.first});
    int back = rev == directed.end() ? 0 : rev->second;
    if (e.first > e.second && back > 0) continue;  // counted from the other side
    int total = n + back;
    if (total == 1) ++c.boundary;
    if (total >= 3) ++c.non_manifold;
    if (n >= 2 || back >= 2) ++c.inconsistent;
  }
  return c;
}

// A ring of n points at distance d from the origin along `axis`, radius r.
JunctionRing ring(glm::vec3 axis, float d, float r, int n, bool reversed = false) {
  JunctionRing jr;
  jr.axis = glm::normalize(axis);
  glm::vec3 u = any_perpendicular(jr.axis), v = glm::cross(jr.axis, u);
  for (int k = 0; k < n; ++k) {
    double t = 2.0 * kPi * (reversed ? -k : k) / n;
    jr.points.push_back(jr.axis * d + r * (float(std::cos(t)) * u + float(std::sin(t)) * v));
  }
  return jr;
}

TreeGraph fork_tree(const std::string& symbols, float angle) {
  TurtleParams p;
  p.angle_deg = angle;
  p.step = 1.0f;
  TreeGraph g = interpret(symbols, p, 1);
  assign_pipe_radii(g, 0.05f, 2.0f);
  return g;
}

}  // namespace

TEST(Bifurcation, SphereAnglesAddUpAndEncloseBothBranches) {
  for (double gamma_deg : {5.0, 20.0, 45.0, 90.0, 120.0, 170.0})
    for (double r1 : {0.1, 0.5, 1.0})
      for (double r2 : {0.1, 0.3, 1.0}) {
        double gamma = gamma_deg * kPi / 180.0;
        BifurcationSphere s = bifurcation_sphere(r1, r2, gamma);
        EXPECT_NEAR(s.alpha + s.beta, gamma, 1e-12);
        EXPECT_GE(s.radius, std::max(r1, r2) * (1.0 - 1e-12));
        EXPECT_NEAR(s.radius, r2 / std::sin(s.beta), 1e-9 * s.radius);  // r1 / sin α = r2 / sin β
        // tan β = sin γ / (r1/r2 + cos γ), written without the division (β may be 90°).
        EXPECT_NEAR(std::sin(s.beta) * (r1 / r2 + std::cos(gamma)), std::cos(s.beta) * std::sin(gamma), 1e-12);
        EXPECT_NEAR(std::sin(s.alpha) * (r2 / r1 + std::cos(gamma)), std::cos(s.alpha) * std::sin(gamma), 1e-12);
      }
  // Equal radii: the crotch lies on the bisector, at r / sin(γ / 2).
  BifurcationSphere e = bifurcation_sphere(1.0, 1.0, kPi / 3);
  EXPECT_NEAR(e.alpha, kPi / 6, 1e-12);
  EXPECT_NEAR(e.radius, 2.0, 1e-12);
  // Narrow forks need larger spheres; clamping keeps them finite.
  EXPECT_GT(bifurcation_sphere(1.0, 1.0, 0.1).radius, bifurcation_sphere(1.0, 1.0, 0.5).radius);
  BifurcationSphere c = bifurcation_sphere(1.0, 0.5, 0.0, 0.2, 2.5);
  EXPECT_EQ(c.gamma, 0.2);
  EXPECT_TRUE(std::isfinite(c.radius));
  EXPECT_NEAR(c.alpha + c.beta, 0.2, 1e-12);
}

TEST(Bifurcation, ConvexHullOfPointsOnASphere) {
  std::vector<glm::dvec3> pts;
  for (int i = 0; i < 40; ++i) {  // a Fibonacci sphere
    double z = 1.0 - 2.0 * (i + 0.5) / 40.0, r = std::sqrt(1 - z * z), phi = i * 2.399963;
    pts.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
  }
  std::vector<std::array<uint32_t, 3>> faces;
  ASSERT_TRUE(convex_hull(pts, &faces));
  EXPECT_EQ(faces.size(), 2 * pts.size() - 4);  // Euler: every point is a hull vertex
  for (const auto& f : faces) {
    glm::dvec3 n = glm::cross(pts[f[1]] - pts[f[0]], pts[f[2]] - pts[f[0]]);
    EXPECT_GT(glm::dot(n, pts[f[0]] + pts[f[1]] + pts[f[2]]), 0.0);  // outward
  }
  std::vector<glm::dvec3> flat = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  EXPECT_FALSE(convex_hull(flat, &faces));
}

TEST(Bifurcation, JoinedRingsLeaveOnlyTheRingEdgesOpen) {
  // A Y: an incoming ring below, two children above at ±30°, different side counts.
  std::vector<JunctionRing> rings = {
      ring({0, -1, 0}, 1.0f, 0.4f, 8, /*reversed=*/true), ring({0.5f, 0.866f, 0}, 1.2f, 0.3f, 6),
      ring({-0.5f, 0.866f, 0.1f}, 1.2f, 0.25f, 5)};
  std::vector<std::array<RingVertex, 3>> tris;
  ASSERT_TRUE(join_rings(glm::vec3(0.0f), rings, &tris));
  EXPECT_EQ(tris.size(), 8u + 6u + 5u + 2u * 3u - 4u);  // Σ n + 2k − 4
  // Each ring edge once, the other edges twice in opposite directions.
  std::map<std::pair<uint64_t, uint64_t>, int> directed;
  auto key = [](RingVertex v) { return (uint64_t(v.ring) << 32) | v.index; };
  for (const auto& t : tris) {
    EXPECT_FALSE(t[0].ring == t[1].ring && t[1].ring == t[2].ring);
    for (int k = 0; k < 3; ++k) directed[{key(t[k]), key(t[(k + 1) % 3])}]++;
    // Outward seen from the fork.
    glm::vec3 a = rings[t[0].ring].points[t[0].index], b = rings[t[1].ring].points[t[1].index],
              c = rings[t[2].ring].points[t[2].index];
    EXPECT_GT(glm::dot(glm::cross(b - a, c - a), a + b + c), 0.0f);
  }
  size_t open = 0;
  for (const auto& [e, n] : directed) {
    EXPECT_EQ(n, 1);
    if (!directed.count({e.second, e.first})) {
      ++open;
      EXPECT_EQ(e.first >> 32, e.second >> 32);  // an open edge is a ring edge
    }
  }
  EXPECT_EQ(open, 8u + 6u + 5u);
  // Overlapping cross-sections (two rings almost along the same axis) cannot be joined.
  std::vector<JunctionRing> bad = {ring({0, -1, 0}, 1.0f, 0.4f, 6), ring({0, 1, 0}, 1.0f, 0.4f, 6),
                                   ring({0.05f, 1, 0}, 1.0f, 0.4f, 6)};
  EXPECT_FALSE(join_rings(glm::vec3(0.0f), bad, &tris));
  EXPECT_TRUE(tris.empty());
}

TEST(Bifurcation, ForkMeshIsClosedExceptTheBase) {
  for (const char* symbols : {"FF[+FF]FF", "FF[+FF][-FF]FF", "FF[&F][^F][+F][-F]FF", "F[+F]F[-F]F[+F]F"}) {
    TreeGraph g = fork_tree(symbols, 40.0f);
    BranchMeshInfo info;
    Mesh m = mesh_branches(g, {}, &info);
    EdgeCensus c = census(m);
    EXPECT_EQ(c.boundary, info.base_ring_sides) << symbols;
    EXPECT_GT(info.base_ring_sides, 0u);
    EXPECT_EQ(c.non_manifold, 0u) << symbols;
    EXPECT_EQ(c.inconsistent, 0u) << symbols;
    EXPECT_EQ(count_boundary_edges(m), info.base_ring_sides);
    EXPECT_GT(info.junctions, 0u) << symbols;
    EXPECT_EQ(info.embedded_starts, 0u) << symbols;  // clean forks are all really joined
  }
}

TEST(Bifurcation, BranchesAreCutBackToTheSphere) {
  // Nodes: 0 root, 1, 2 = fork, 3-4 side branch (made thinner), 5-6 continuation. The
  // trunk is straight, so its axis passes through the fork node.
  TreeGraph g = fork_tree("FF[+FF]FF", 45.0f);
  g.nodes[3].radius = g.nodes[4].radius = 0.03f;
  g.nodes[2].radius = g.nodes[1].radius = g.nodes[0].radius = std::sqrt(0.03f * 0.03f + 0.05f * 0.05f);
  BranchMeshInfo info;
  MesherParams p;
  mesh_branches(g, p, &info);
  ASSERT_EQ(info.junctions, 1u);
  const glm::vec3 fork = g.nodes[2].position;
  const double lo = p.min_fork_angle_deg * kPi / 180.0, hi = p.max_fork_angle_deg * kPi / 180.0;
  const float r_in = g.nodes[2].radius, r_side = g.nodes[3].radius, r_on = g.nodes[5].radius;
  // The largest pairwise sphere: incoming/side at 135°, incoming/continuation at 180°,
  // continuation/side at 45°.
  double sphere = std::max({bifurcation_sphere(r_in, r_side, 0.75 * kPi, lo, hi).radius,
                            bifurcation_sphere(r_in, r_on, kPi, lo, hi).radius,
                            bifurcation_sphere(r_on, r_side, 0.25 * kPi, lo, hi).radius});
  EXPECT_GT(sphere, double(std::max({r_in, r_side, r_on})));
  // All three branches are cut on one sphere around the fork, at that radius or a little
  // beyond (the mesher grows it while the cut cross-sections, with the spline's smoothed
  // radii and a small angular margin, still overlap). No ring lies inside it.
  double cut = 1e9;
  for (const TubeRing& r : info.rings) cut = std::min(cut, double(glm::length(r.center - fork)));
  EXPECT_GE(cut, sphere * (1.0 - 1e-4));
  EXPECT_LE(cut, sphere * 1.5);
  size_t near_rings = 0;
  for (const TubeRing& r : info.rings) near_rings += std::abs(glm::length(r.center - fork) - cut) < 1e-4 * cut;
  EXPECT_EQ(near_rings, 3u);
  const double sphere_cut = cut;
  // Disjoint cross-sections: seen from the fork, no two cut rings overlap.
  for (const TubeRing& a : info.rings)
    for (const TubeRing& b : info.rings) {
      double da = glm::length(a.center - fork), db = glm::length(b.center - fork);
      if (&a == &b || da > 1.01 * sphere_cut || db > 1.01 * sphere_cut) continue;
      double angle = std::acos(std::clamp(double(glm::dot(glm::normalize(a.center - fork), glm::normalize(b.center - fork))), -1.0, 1.0));
      EXPECT_GT(angle, std::atan(a.radius / da) + std::atan(b.radius / db));
      // Each cut ring is perpendicular to the ray from the fork through its center.
      EXPECT_NEAR(std::abs(glm::dot(a.tangent, glm::normalize(a.center - fork))), 1.0f, 1e-5f);
    }
}

TEST(Bifurcation, NearlyParallelBranchesFallBackToClosedStarts) {
  // A side branch along its parent (angle 0): no sphere separates them; the child is closed at
  // its start inside the parent, and the mesh still has no hole.
  TreeGraph g = fork_tree("FF[+(1)FF]FF", 30.0f);
  BranchMeshInfo info;
  Mesh m = mesh_branches(g, {}, &info);
  EXPECT_EQ(info.embedded_starts, 1u);
  EXPECT_EQ(count_boundary_edges(m), info.base_ring_sides);
  MesherParams off;
  off.join_forks = false;
  Mesh loose = mesh_branches(fork_tree("FF[+FF][-FF]FF", 30.0f), off, &info);
  EXPECT_EQ(info.junctions, 0u);
  EXPECT_EQ(info.embedded_starts, 2u);
  EXPECT_EQ(count_boundary_edges(loose), info.base_ring_sides);
}

TEST(Bifurcation, EveryPresetIsClosedExceptTheBaseRing) {
  fs::path dir = fs::path(FOREST_SOURCE_DIR) / "scenes" / "species";
  size_t presets = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().extension() != ".toml") continue;
    ++presets;
    TreeModel model = generate_from_species(e.path());
    const Mesh& m = model.branches;
    EdgeCensus c = census(m);
    EXPECT_EQ(c.non_manifold, 0u) << e.path();
    EXPECT_EQ(c.inconsistent, 0u) << e.path();
    // The open edges form the trunk's base ring: one closed loop of 3 to 32 edges, all of
    // them around the root. (None when the root itself forks: its junction closes it.)
    if (c.boundary > 0) EXPECT_GE(c.boundary, 3u) << e.path();
    EXPECT_LE(c.boundary, 32u) << e.path();
    std::map<std::array<float, 3>, int> degree;  // welded vertex -> open edges at it
    std::map<std::pair<std::array<float, 3>, std::array<float, 3>>, int> uses;
    auto pos = [&](uint32_t i) {
      const glm::vec3& p = m.vertices[i].position;
      return std::array<float, 3>{p.x, p.y, p.z};
    };
    for (size_t t = 0; t < m.indices.size(); t += 3)
      for (int k = 0; k < 3; ++k) {
        auto a = pos(m.indices[t + k]), b = pos(m.indices[t + (k + 1) % 3]);
        uses[{std::min(a, b), std::max(a, b)}]++;
      }
    for (const auto& [edge, n] : uses) {
      if (n != 1) continue;
      degree[edge.first]++;
      degree[edge.second]++;
      for (const auto& q : {edge.first, edge.second})
        EXPECT_LT(glm::length(glm::vec3(q[0], q[1], q[2])), 0.5f) << e.path() << ": an open edge away from the root";
    }
    EXPECT_EQ(degree.size(), c.boundary) << e.path();
    for (const auto& [v, d] : degree) EXPECT_EQ(d, 2) << e.path();
  }
  EXPECT_GE(presets, 3u);
}
