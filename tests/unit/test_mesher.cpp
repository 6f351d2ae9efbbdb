// Branch tubes along B-spline axes, their rings, frames and bark UVs, and the bounding sphere.
#include <gtest/gtest.h>

#include "generators/tree/foliage.h"

#include <algorithm>
#include <cmath>

#include "generators/mesh/frames.h"
#include "generators/tree/leaves.h"
#include "generators/methods/lsystem/lsystem.h"
#include "generators/mesh/mesher.h"
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

TEST(Mesher, RingsAreCirclesOfTheirRadiusAroundTheAxis) {
  TreeGraph g = test_tree();
  BranchMeshInfo info;
  Mesh m = mesh_branches(g, {}, &info);
  ASSERT_FALSE(info.rings.empty());
  float r_lo = 1e9f, r_hi = 0.0f;
  for (const TreeNode& n : g.nodes) r_lo = std::min(r_lo, n.radius), r_hi = std::max(r_hi, n.radius);
  for (size_t k = 0; k < info.rings.size(); ++k) {
    const TubeRing& r = info.rings[k];
    EXPECT_GE(r.sides, 3u);
    EXPECT_LE(r.sides, 8u);
    // The spline's radius stays within the node radii (its weights are convex).
    EXPECT_GE(r.radius, r_lo * 0.999f);
    EXPECT_LE(r.radius, r_hi * 1.001f);
    EXPECT_NEAR(glm::length(r.tangent), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(r.normal, r.tangent), 0.0f, 1e-5f);
    for (uint32_t j = 0; j <= r.sides; ++j) {
      const Vertex& v = m.vertices[r.first_vertex + j];
      glm::vec3 d = v.position - r.center;
      EXPECT_NEAR(glm::length(d), r.radius, 1e-4f * r.radius + 1e-6f);
      EXPECT_NEAR(glm::dot(d, r.tangent), 0.0f, 1e-3f * r.radius + 1e-6f);  // in the plane ⊥ T
      EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-5f);
      EXPECT_GT(glm::dot(v.normal, d), 0.99f * r.radius);  // radial, outward
      // u along the ring's polygon (tile 1 m by default), from −perimeter/2 at vertex 0 to
      // +perimeter/2 at its seam copy.
      const float perimeter = float(r.sides) * 2.0f * r.radius * std::sin(3.14159265f / float(r.sides));
      EXPECT_NEAR(v.uv.x, (float(j) / float(r.sides) - 0.5f) * perimeter, 1e-5f * perimeter);
    }
    // Vertex 0 lies along the frame's normal; the seam vertex repeats it exactly.
    EXPECT_NEAR(glm::length(m.vertices[r.first_vertex].position - (r.center + r.radius * r.normal)), 0.0f, 1e-5f);
    EXPECT_EQ(m.vertices[r.first_vertex].position, m.vertices[r.first_vertex + r.sides].position);
    if (k > 0 && info.rings[k - 1].chain == r.chain) {
      EXPECT_EQ(r.sides, info.rings[k - 1].sides);
    }
  }
  // Every tip ends in one apex (the last piece of each chain tapers to a point).
  auto children = children_of(g);
  size_t tips = 0;
  for (size_t i = 1; i < children.size(); ++i) tips += children[i].empty();
  EXPECT_EQ(info.cap_vertices.size(), tips);
  EXPECT_EQ(info.chains, tips);
}

TEST(Mesher, TrianglesAreValidAndWoundOutward) {
  TreeGraph g = test_tree();
  BranchMeshInfo info;
  Mesh m = mesh_branches(g, {}, &info);
  ASSERT_EQ(m.indices.size() % 3, 0u);
  // Vertex -> piece, and each piece's axis polyline (ring centers, then its apex).
  std::vector<int> piece_of(m.vertices.size(), -1);
  std::vector<std::vector<glm::vec3>> axis(info.pieces);
  for (const TubeRing& r : info.rings) {
    for (uint32_t j = 0; j <= r.sides; ++j) piece_of[r.first_vertex + j] = int(r.piece);
    axis[r.piece].push_back(r.center);
  }
  // A start cap's center and its copies of the ring's vertices, then the apex, follow their
  // piece's last ring.
  for (uint32_t c : info.start_cap_vertices)
    for (const TubeRing& r : info.rings)
      if (int(r.piece) == piece_of[c - 1]) {
        for (uint32_t j = 0; j <= r.sides; ++j) piece_of[c + j] = piece_of[c - 1];
        break;
      }
  for (uint32_t apex : info.cap_vertices) {
    int piece = piece_of[apex - 1];
    piece_of[apex] = piece;
    axis[size_t(piece)].push_back(m.vertices[apex].position);
  }
  size_t tube = 0, cone = 0, junction = 0, start_caps = 0;
  double signed_volume = 0.0;
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
    signed_volume += glm::dot(glm::dvec3(a), glm::cross(glm::dvec3(b), glm::dvec3(c))) / 6.0;
    int piece = piece_of[ia];
    if (piece < 0 || piece_of[ib] != piece || piece_of[ic] != piece) {
      ++junction;  // joins the rings of several pieces
      continue;
    }
    if (std::find(info.start_cap_vertices.begin(), info.start_cap_vertices.end(), ia) != info.start_cap_vertices.end()) {
      ++start_caps;  // flat, facing back along the branch
      continue;
    }
    glm::vec3 centroid = (a + b + c) / 3.0f;
    const auto& poly = axis[size_t(piece)];
    glm::vec3 best = poly[0];
    for (size_t k = 0; k + 1 < poly.size(); ++k) {
      glm::vec3 q = closest_on_segment(centroid, poly[k], poly[k + 1]);
      if (glm::length(centroid - q) < glm::length(centroid - best)) best = q;
    }
    EXPECT_GT(glm::dot(glm::normalize(n), glm::normalize(centroid - best)), 0.0f)
        << "triangle " << t / 3 << " faces inward";
    bool is_cone = std::find(info.cap_vertices.begin(), info.cap_vertices.end(), ic) != info.cap_vertices.end();
    (is_cone ? cone : tube)++;
  }
  // 2n triangles per ring pair of a piece, n per tip cone, the rest joins forks.
  size_t expect_tube = 0, expect_cone = 0;
  for (size_t k = 0; k < info.rings.size(); ++k) {
    bool last = k + 1 == info.rings.size() || info.rings[k + 1].piece != info.rings[k].piece;
    if (!last) expect_tube += 2 * info.rings[k].sides;
  }
  for (uint32_t apex : info.cap_vertices) {
    const TubeRing* last = nullptr;  // the apex's piece's last ring
    for (const TubeRing& r : info.rings)
      if (r.piece == uint32_t(piece_of[apex])) last = &r;
    ASSERT_NE(last, nullptr);
    expect_cone += last->sides;
  }
  EXPECT_EQ(tube, expect_tube);
  EXPECT_EQ(cone, expect_cone);
  EXPECT_EQ(junction, info.junction_triangles);
  size_t expect_start_caps = 0;
  for (uint32_t c : info.start_cap_vertices)
    for (const TubeRing& r : info.rings)
      if (r.piece == uint32_t(piece_of[c])) {
        expect_start_caps += r.sides;
        break;
      }
  EXPECT_EQ(start_caps, expect_start_caps);
  EXPECT_EQ(info.start_cap_vertices.size(), info.embedded_starts);
  EXPECT_GT(info.junctions, 0u);
  // Closed and consistently oriented (test_bifurcation), so a positive volume means every
  // triangle faces outward; the open base ring only adds a thin sliver.
  EXPECT_GT(signed_volume, 0.0);
}

TEST(Mesher, StraightPartsGetFewRingsBendsMore) {
  MesherParams p;
  BranchMeshInfo info;
  mesh_branches(straight("FFFFFFFFFF"), p, &info);
  ASSERT_EQ(info.rings.size(), 1u);  // a straight pole: the base ring, then the apex
  EXPECT_EQ(info.cap_vertices.size(), 1u);
  mesh_branches(straight("FFFFF+FFFFF"), p, &info);
  size_t bent = info.rings.size();
  EXPECT_GE(bent, 2u);  // a 30° bend needs rings along the spline's turn
  p.max_bend_deg = 5.0f;
  mesh_branches(straight("FFFFF+FFFFF"), p, &info);
  EXPECT_GT(info.rings.size(), bent);
  // Consecutive rings turn by about the maximum bend at most.
  for (size_t k = 1; k < info.rings.size(); ++k)
    EXPECT_LT(std::acos(std::min(1.0f, glm::dot(info.rings[k].tangent, info.rings[k - 1].tangent))),
              2.0f * 5.0f * 3.14159265f / 180.0f);
}

TEST(Mesher, ParallelTransportedRingsDoNotTwist) {
  TreeGraph g = test_tree();
  BranchMeshInfo info;
  mesh_branches(g, {}, &info);
  size_t checked = 0;
  for (size_t k = 1; k < info.rings.size(); ++k) {
    const TubeRing &a = info.rings[k - 1], &b = info.rings[k];
    if (a.piece != b.piece) continue;
    // The next frame is the previous one turned by the minimal rotation between tangents.
    glm::vec3 carried = transport(a.normal, a.tangent, b.tangent);
    EXPECT_NEAR(glm::dot(carried, b.normal), 1.0f, 1e-4f) << k;
    ++checked;
  }
  EXPECT_GT(checked, 10u);
}

TEST(Mesher, BarkUvAreMetresOverTheTileSize) {
  // Along a tube of constant radius r, v falls by arc length / tile (toward the tip) and u
  // steps by one polygon side's length / tile: the same texel density whatever the radius.
  MesherParams p;
  p.max_bend_deg = 1.0f;
  p.bark_tile_meters = 0.4f;
  BranchMeshInfo info;
  TreeGraph g = straight("FFFF+FFFF");  // pipe radii: constant along a single chain
  Mesh m = mesh_branches(g, p, &info);
  ASSERT_GE(info.rings.size(), 3u);
  for (size_t k = 1; k < info.rings.size(); ++k) {
    const TubeRing &a = info.rings[k - 1], &b = info.rings[k];
    float dv = m.vertices[b.first_vertex].uv.y - m.vertices[a.first_vertex].uv.y;
    float arc = glm::length(b.center - a.center);
    EXPECT_NEAR(dv, -arc / p.bark_tile_meters, 0.02f * std::abs(dv) + 1e-4f);
    const Vertex &v0 = m.vertices[b.first_vertex], &v1 = m.vertices[b.first_vertex + 1];
    EXPECT_NEAR(v1.uv.x - v0.uv.x, glm::length(v1.position - v0.position) / p.bark_tile_meters, 1e-5f);
  }
  // A thinner branch: the same v per metre, half the u around.
  TreeGraph thin = g;
  for (TreeNode& n : thin.nodes) n.radius *= 0.5f;
  BranchMeshInfo thin_info;
  Mesh tm = mesh_branches(thin, p, &thin_info);
  ASSERT_EQ(thin_info.rings.size(), info.rings.size());
  const TubeRing &thick_ring = info.rings.back(), &thin_ring = thin_info.rings.back();
  EXPECT_NEAR(tm.vertices[thin_ring.first_vertex].uv.y, m.vertices[thick_ring.first_vertex].uv.y, 1e-4f);
  EXPECT_NEAR(tm.vertices[thin_ring.first_vertex].uv.x, 0.5f * m.vertices[thick_ring.first_vertex].uv.x, 1e-5f);
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
  EXPECT_EQ(info.base_ring_sides, 10u);
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

TEST(BoundingSphere, ContainsEverythingAndIsTight) {
  TreeGraph g = test_tree();
  FoliageKeys foliage;
  foliage.shoot_length = 0.3f;
  foliage.per_tip = 3;
  place_foliage(g, foliage, 9);
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
