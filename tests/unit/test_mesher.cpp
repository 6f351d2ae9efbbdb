// Branch tubes, leaf card and bounding sphere.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "generators/tree/leaves.h"
#include "generators/tree/lsystem.h"
#include "generators/tree/mesher.h"
#include "generators/tree/pipe_model.h"

using namespace forest;

namespace {

// A 3D stochastic plant with curved branches (tropism), jittered steps and pipe radii.
TreeGraph test_tree(uint64_t seed = 3) {
  LSystem s{"X", {{'X', "F[[X]-X]F[+FX]-X", 1.0}, {'X', "F[&X]F[^FX]", 1.0}, {'F', "FF", 1.0}}};
  TurtleParams p;
  p.angle_deg = 25.0f;
  p.angle_jitter_deg = 8.0f;
  p.roll_jitter_deg = 180.0f;
  p.step = 0.2f;
  p.step_jitter = 0.3f;
  p.tropism_strength = 0.08f;
  TreeGraph g = interpret(rewrite(s, 4, seed), p, seed);
  assign_pipe_radii(g, 0.004f, 2.3f);
  return g;
}

TreeGraph straight(const std::string& symbols) {
  TurtleParams p;
  p.angle_deg = 30.0f;
  p.step = 0.5f;
  TreeGraph g = interpret(symbols, p, 1);
  assign_pipe_radii(g, 0.05f, 2.0f);
  return g;
}

glm::vec3 closest_on_segment(glm::vec3 p, glm::vec3 a, glm::vec3 b) {
  glm::vec3 ab = b - a;
  float t = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0f, 1.0f);
  return a + t * ab;
}

}  // namespace

TEST(Mesher, RingsAreCirclesOfTheNodeRadiusAroundTheAxis) {
  TreeGraph g = test_tree();
  BranchMeshInfo info;
  Mesh m = mesh_branches(g, {}, &info);
  auto children = children_of(g);
  ASSERT_FALSE(info.rings.empty());
  size_t expected_vertices = info.cap_vertices.size();
  for (size_t k = 0; k < info.rings.size(); ++k) {
    const TubeRing& r = info.rings[k];
    expected_vertices += r.sides + 1;
    EXPECT_GE(r.sides, 3u);
    EXPECT_LE(r.sides, 8u);
    EXPECT_EQ(r.center, g.nodes[r.node].position);
    // The radius is the node's, except the first ring of a side chain, which starts at its
    // parent with the branch's own radius.
    bool first_of_chain = k == 0 || info.rings[k - 1].chain != r.chain;
    bool ok = r.radius == g.nodes[r.node].radius;
    if (!ok && first_of_chain)
      for (uint32_t c : children[r.node]) ok = ok || r.radius == g.nodes[c].radius;
    EXPECT_TRUE(ok) << "ring " << k;
    EXPECT_NEAR(glm::length(r.tangent), 1.0f, 1e-5f);
    for (uint32_t j = 0; j <= r.sides; ++j) {
      const Vertex& v = m.vertices[r.first_vertex + j];
      glm::vec3 d = v.position - r.center;
      EXPECT_NEAR(glm::length(d), r.radius, 1e-4f * r.radius + 1e-6f);
      EXPECT_NEAR(glm::dot(d, r.tangent), 0.0f, 1e-3f * r.radius + 1e-6f);
      EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-5f);
      EXPECT_GT(glm::dot(v.normal, d), 0.99f * r.radius);  // radial, outward
      EXPECT_NEAR(v.uv.x, float(j) / float(r.sides), 1e-6f);
    }
    // The seam vertex repeats the first position exactly.
    EXPECT_EQ(m.vertices[r.first_vertex].position, m.vertices[r.first_vertex + r.sides].position);
    if (!first_of_chain) {
      EXPECT_EQ(r.sides, info.rings[k - 1].sides);
    }
  }
  EXPECT_EQ(m.vertices.size(), expected_vertices);
  // One chain per tip (each chain ends in exactly one tip), each closed by one cone.
  size_t tips = 0;
  for (size_t i = 1; i < children.size(); ++i) tips += children[i].empty();
  EXPECT_EQ(info.cap_vertices.size(), tips);
}

TEST(Mesher, TrianglesAreValidAndWoundOutward) {
  TreeGraph g = test_tree();
  BranchMeshInfo info;
  Mesh m = mesh_branches(g, {}, &info);
  ASSERT_EQ(m.indices.size() % 3, 0u);
  // Vertex -> chain, and each chain's axis polyline (ring centers, then the cone apex).
  std::vector<int> chain_of(m.vertices.size(), -1);
  std::vector<std::vector<glm::vec3>> axis(info.cap_vertices.size());
  for (const TubeRing& r : info.rings) {
    for (uint32_t j = 0; j <= r.sides; ++j) chain_of[r.first_vertex + j] = int(r.chain);
    axis[r.chain].push_back(r.center);
  }
  for (size_t c = 0; c < info.cap_vertices.size(); ++c) chain_of[info.cap_vertices[c]] = int(c);
  for (int c : chain_of) ASSERT_GE(c, 0);

  size_t side = 0, cap = 0;
  for (size_t t = 0; t < m.indices.size(); t += 3) {
    uint32_t ia = m.indices[t], ib = m.indices[t + 1], ic = m.indices[t + 2];
    ASSERT_LT(ia, m.vertices.size());
    ASSERT_LT(ib, m.vertices.size());
    ASSERT_LT(ic, m.vertices.size());
    ASSERT_TRUE(ia != ib && ib != ic && ia != ic);
    glm::vec3 a = m.vertices[ia].position, b = m.vertices[ib].position, c = m.vertices[ic].position;
    glm::vec3 n = glm::cross(b - a, c - a);
    float longest = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
    EXPECT_GT(glm::length(n), 1e-6f * longest * longest) << "degenerate triangle " << t / 3;
    int chain = chain_of[ia];
    EXPECT_EQ(chain_of[ib], chain);
    EXPECT_EQ(chain_of[ic], chain);
    glm::vec3 centroid = (a + b + c) / 3.0f;
    const auto& poly = axis[size_t(chain)];
    glm::vec3 best = poly[0];
    for (size_t k = 0; k + 1 < poly.size(); ++k) {
      glm::vec3 q = closest_on_segment(centroid, poly[k], poly[k + 1]);
      if (glm::length(centroid - q) < glm::length(centroid - best)) best = q;
    }
    EXPECT_GT(glm::dot(glm::normalize(n), glm::normalize(centroid - best)), 0.0f)
        << "triangle " << t / 3 << " faces inward";
    bool is_cap = std::find(info.cap_vertices.begin(), info.cap_vertices.end(), ic) != info.cap_vertices.end();
    (is_cap ? cap : side)++;
  }
  // Triangle count: 2 per side per ring pair, 1 per side per cap.
  size_t expect_side = 0, expect_cap = 0;
  for (size_t k = 0; k < info.rings.size(); ++k) {
    bool last = k + 1 == info.rings.size() || info.rings[k + 1].chain != info.rings[k].chain;
    (last ? expect_cap : expect_side) += last ? info.rings[k].sides : 2 * info.rings[k].sides;
  }
  EXPECT_EQ(side, expect_side);
  EXPECT_EQ(cap, expect_cap);
}

TEST(Mesher, CollinearNodesAreSkippedButEndsKept) {
  MesherParams p;
  BranchMeshInfo info;
  mesh_branches(straight("FFFFFFFFFF"), p, &info);
  ASSERT_EQ(info.rings.size(), 2u);  // a straight pipe: both ends only
  EXPECT_EQ(info.rings[0].node, 0u);
  EXPECT_EQ(info.rings[1].node, 10u);
  mesh_branches(straight("FFFFF+FFFFF"), p, &info);
  ASSERT_EQ(info.rings.size(), 3u);  // plus the bend
  EXPECT_EQ(info.rings[1].node, 5u);
  // A side branch halves the pipe: a ring where the radius changes, even when straight.
  mesh_branches(straight("FFFF[+F]FFFF"), p, &info);
  size_t main_rings = 0;
  for (const TubeRing& r : info.rings) main_rings += r.chain == 0;
  EXPECT_EQ(main_rings, 3u);
  p.radius_tolerance = -1.0f;  // keep everything
  mesh_branches(straight("FFFFFFFFFF"), p, &info);
  EXPECT_EQ(info.rings.size(), 11u);
}

TEST(Mesher, ParallelTransportDoesNotTwistStraightTubes) {
  MesherParams p;
  p.radius_tolerance = -1.0f;
  BranchMeshInfo info;
  TreeGraph g = straight("FFFFF");
  Mesh m = mesh_branches(g, p, &info);
  glm::vec3 first = m.vertices[info.rings[0].first_vertex].position - info.rings[0].center;
  for (const TubeRing& r : info.rings) {
    glm::vec3 d = m.vertices[r.first_vertex].position - r.center;
    EXPECT_NEAR(glm::length(d - first), 0.0f, 1e-5f);
  }
  // v grows along the tube in units of its circumference.
  float circ = 2.0f * 3.14159265f * info.rings[0].radius;
  for (size_t k = 0; k < info.rings.size(); ++k)
    EXPECT_NEAR(m.vertices[info.rings[k].first_vertex].uv.y, 0.5f * float(k) / circ, 1e-4f);
}

TEST(Mesher, SidesFollowTheChainBaseRadius) {
  MesherParams p;
  p.min_sides = 3;
  p.max_sides = 10;
  EXPECT_EQ(ring_sides(1.0f, 1.0f, p), 10);
  EXPECT_EQ(ring_sides(0.001f, 1.0f, p), 3);
  EXPECT_LE(ring_sides(0.25f, 1.0f, p), ring_sides(0.5f, 1.0f, p));
  BranchMeshInfo info;
  mesh_branches(test_tree(), p, &info);
  EXPECT_EQ(info.rings[0].sides, 10u);  // the trunk
  uint32_t thinnest = 99;
  for (const TubeRing& r : info.rings) thinnest = std::min(thinnest, r.sides);
  // The thinnest chains are the tips' (radius 0.004), relative to the trunk.
  EXPECT_EQ(thinnest, uint32_t(ring_sides(0.004f, info.rings[0].radius, p)));
  EXPECT_LT(thinnest, 10u);
}

TEST(Mesher, PureFunction) {
  TreeGraph g = test_tree();
  Mesh a = mesh_branches(g), b = mesh_branches(g);
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  EXPECT_EQ(a.indices, b.indices);
  for (size_t i = 0; i < a.vertices.size(); ++i) EXPECT_EQ(a.vertices[i].position, b.vertices[i].position);
  TreeGraph empty;
  empty.nodes.push_back(TreeNode{});
  EXPECT_TRUE(mesh_branches(empty).vertices.empty());
}

TEST(LeafCard, BladeAlongYNormalZ) {
  Mesh card = make_leaf_card();
  ASSERT_EQ(card.vertices.size(), 6u);
  ASSERT_EQ(card.indices.size(), 12u);
  float min_y = 1e9f, max_y = -1e9f;
  for (const Vertex& v : card.vertices) {
    EXPECT_EQ(v.normal, glm::vec3(0, 0, 1));
    EXPECT_EQ(v.position.z, 0.0f);
    EXPECT_LT(std::abs(v.position.x), 0.5f);
    min_y = std::min(min_y, v.position.y);
    max_y = std::max(max_y, v.position.y);
    EXPECT_GE(v.uv.x, 0.0f);
    EXPECT_LE(v.uv.x, 1.0f);
  }
  EXPECT_EQ(min_y, 0.0f);
  EXPECT_EQ(max_y, 1.0f);
  EXPECT_EQ(card.vertices[0].position, glm::vec3(0, 0, 0));
  for (size_t t = 0; t < card.indices.size(); t += 3) {
    glm::vec3 a = card.vertices[card.indices[t]].position, b = card.vertices[card.indices[t + 1]].position,
              c = card.vertices[card.indices[t + 2]].position;
    EXPECT_GT(glm::cross(b - a, c - a).z, 1e-3f);  // counter-clockwise seen from +Z
  }
}

TEST(BoundingSphere, ContainsEverythingAndIsTight) {
  TreeGraph g = test_tree();
  LeafParams lp;
  lp.size = 0.3f;
  lp.per_tip = 3;
  place_twig_leaves(g, lp, 9);
  Mesh branches = mesh_branches(g);
  Mesh card = make_leaf_card();
  glm::vec4 s = bounding_sphere(branches, card, g.leaves);
  glm::vec3 c(s), lo(1e9f), hi(-1e9f);
  auto check = [&](glm::vec3 p) {
    EXPECT_LE(glm::length(p - c), s.w);
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  };
  for (const Vertex& v : branches.vertices) check(v.position);
  for (const LeafPlacement& l : g.leaves)
    for (const Vertex& v : card.vertices) check(leaf_to_model(l, v.position));
  glm::vec3 ext = hi - lo;
  EXPECT_GE(s.w, 0.5f * std::max({ext.x, ext.y, ext.z}));
  EXPECT_LE(s.w, 0.5f * glm::length(ext) * 1.05f);  // no worse than the box's sphere
  // Leaves count: a sphere of the branches alone can be smaller.
  glm::vec4 bare = bounding_sphere(branches, card, {});
  EXPECT_LE(bare.w, s.w);
  EXPECT_EQ(bounding_sphere(Mesh{}, card, {}), glm::vec4(0.0f));
}
