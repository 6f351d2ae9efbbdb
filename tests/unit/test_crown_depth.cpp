// The convex hull (generators/tree/convex_hull.h) and leaf depths below it
// (generators/tree/crown_depth.h) on point sets with known answers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "generators/core/rng.h"
#include "generators/core/hull_2d.h"
#include "generators/tree/convex_hull.h"
#include "generators/tree/crown_depth.h"

using namespace forest;

namespace {

glm::vec3 in_ball(Rng& rng, float radius) {
  for (;;) {
    glm::vec3 p(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
    if (glm::dot(p, p) <= 1.0f) return p * radius;
  }
}

glm::vec3 on_sphere(Rng& rng) {
  glm::vec3 p;
  do p = in_ball(rng, 1.0f);
  while (glm::length(p) < 0.1f);
  return glm::normalize(p);
}

// Every point on or inside every plane.
void expect_contains(const ConvexHull& hull, const std::vector<glm::vec3>& points) {
  for (const HullPlane& h : hull.planes) {
    EXPECT_NEAR(glm::length(h.normal), 1.0, 1e-12);
    for (glm::vec3 p : points) ASSERT_LE(glm::dot(h.normal, glm::dvec3(p)) - h.offset, 10 * hull.tolerance);
  }
}

std::vector<LeafPlacement> leaves_at(const std::vector<glm::vec3>& points) {
  std::vector<LeafPlacement> out(points.size());
  for (size_t i = 0; i < points.size(); ++i) out[i].position = points[i];
  return out;
}

}  // namespace

TEST(ConvexHull, CubeWithInteriorAndFacePoints) {
  std::vector<glm::vec3> p;
  for (int i = 0; i < 8; ++i) p.push_back({i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : -1.0f});
  Rng rng(3);
  for (int i = 0; i < 500; ++i) p.push_back({rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)});
  for (int i = 0; i < 60; ++i) p.push_back({float(rng.uniform(-1, 1)), float(rng.uniform(-1, 1)), 1.0f});  // on a face
  ConvexHull hull = convex_hull(p);
  ASSERT_TRUE(hull.solid());
  EXPECT_EQ(hull.triangles.size(), 12u);  // two per face: points on a face are not vertices
  for (glm::uvec3 t : hull.triangles)
    for (int k = 0; k < 3; ++k) EXPECT_LT(t[k], 8u);
  expect_contains(hull, p);
  EXPECT_NEAR(depth_below_hull(hull, {0, 0, 0}), 1.0, 1e-12);
  EXPECT_NEAR(depth_below_hull(hull, {0.5, 0.2, -0.1}), 0.5, 1e-12);
  EXPECT_NEAR(depth_below_hull(hull, {0.3, -0.2, 1.0}), 0.0, 1e-12);
  EXPECT_EQ(depth_below_hull(hull, {3, 0, 0}), 0.0);  // outside
}

// A lattice: many coplanar and collinear points, the hard case of quickhull. The hull may
// triangulate its faces through lattice points, but every plane is one of the six faces.
TEST(ConvexHull, LatticeOfCoplanarPoints) {
  std::vector<glm::vec3> p;
  for (int x = 0; x <= 10; ++x)
    for (int y = 0; y <= 10; ++y)
      for (int z = 0; z <= 10; ++z) p.push_back(glm::vec3(x, y, z) * 0.3f + glm::vec3(5.0f, -2.0f, 7.0f));
  ConvexHull hull = convex_hull(p);
  ASSERT_TRUE(hull.solid());
  expect_contains(hull, p);
  for (const HullPlane& h : hull.planes) {
    glm::dvec3 a = glm::abs(h.normal);
    EXPECT_NEAR(std::max({a.x, a.y, a.z}), 1.0, 1e-9);
  }
  EXPECT_NEAR(depth_below_hull(hull, glm::dvec3(5.0 + 1.5, -2.0 + 1.5, 7.0 + 1.5)), 1.5, 1e-6);
  EXPECT_NEAR(depth_below_hull(hull, glm::dvec3(5.3, -0.5, 8.5)), 0.3, 1e-6);
}

// Points on a sphere are all hull vertices: depth 0 for every one of them (up to the grid).
TEST(ConvexHull, PointsOnASphereAreOnTheSurface) {
  Rng rng(9);
  std::vector<glm::vec3> p;
  for (int i = 0; i < 3000; ++i) p.push_back(on_sphere(rng) * 4.0f + glm::vec3(1.0f, 10.0f, -3.0f));
  ConvexHull hull = convex_hull(p);
  ASSERT_TRUE(hull.solid());
  expect_contains(hull, p);
  // A closed triangulated sphere: F = 2V − 4 when every point is a vertex.
  EXPECT_EQ(hull.triangles.size(), 2 * p.size() - 4);
  for (double d : depths_below_hull(p)) EXPECT_LE(d, hull.tolerance);  // snapped to the grid
  EXPECT_NEAR(depth_below_hull(hull, glm::dvec3(1.0, 10.0, -3.0)), 4.0, 0.05);
}

// Leaves as presets place them: runs of collinear points along straight shoots, a dozen
// leaves sharing each tip, points a few millimetres apart. A hull that decided visibility
// with a tolerance folded over such input (salix_alba: one inverted face, every depth 0).
TEST(ConvexHull, ShootsWithRepeatedAndCollinearLeaves) {
  for (uint64_t seed : {1u, 2u, 3u}) {
    Rng rng(seed);
    std::vector<glm::vec3> p;
    for (int shoot = 0; shoot < 300; ++shoot) {
      glm::vec3 start = in_ball(rng, 6.0f) + glm::vec3(0.0f, 8.0f, 0.0f), dir = on_sphere(rng);
      for (int k = 0; k < 6; ++k) p.push_back(start + dir * (0.05f * float(k)));
      for (int k = 0; k < 14; ++k) p.push_back(start + dir * 0.3f);
      p.push_back(start + dir * 0.3f + glm::vec3(0.002f, 0.0f, 0.0f));
    }
    ConvexHull hull = convex_hull(p);
    ASSERT_TRUE(hull.solid());
    expect_contains(hull, p);
    std::vector<double> depth = depths_below_hull(p);
    std::sort(depth.begin(), depth.end());
    EXPECT_GT(quantile(depth, 0.5), 0.5) << seed;  // most shoots are well inside a 6 m ball
  }
}

// Five leaves of salix_alba (the last three nearly collinear, on one shoot) on which a
// tolerance-based hull folded: a face turned inwards, 0.64 m off.
TEST(ConvexHull, NearlyCollinearLeavesDoNotFoldTheHull) {
  std::vector<glm::vec3> p = {{4.42754364f, 5.48270512f, 7.72713566f},
                              {5.74733019f, 7.56216764f, -5.25017977f},
                              {5.91829681f, 7.853405f, 5.78427744f},
                              {6.23081541f, 7.65319443f, 5.88735533f},
                              {6.38707447f, 7.55308914f, 5.93889427f}};
  ConvexHull hull = convex_hull(p);
  ASSERT_TRUE(hull.solid());
  expect_contains(hull, p);
  // A closed surface: every directed edge has its reverse.
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  for (glm::uvec3 t : hull.triangles)
    for (int k = 0; k < 3; ++k) edges.push_back({t[k], t[(k + 1) % 3]});
  for (auto [a, b] : edges) EXPECT_NE(std::find(edges.begin(), edges.end(), std::make_pair(b, a)), edges.end());
}

TEST(ConvexHull, FlatOrTinyInputHasNoVolume) {
  std::vector<glm::vec3> flat;
  for (int i = 0; i < 50; ++i) flat.push_back({float(i % 7), 2.0f, float(i / 7)});
  EXPECT_FALSE(convex_hull(flat).solid());
  for (double d : depths_below_hull(flat)) EXPECT_EQ(d, 0.0);
  std::vector<glm::vec3> three = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_FALSE(convex_hull(three).solid());
  EXPECT_FALSE(convex_hull({}).solid());
  std::vector<glm::vec3> same(20, glm::vec3(1.0f));
  EXPECT_FALSE(convex_hull(same).solid());
}

TEST(CrownDepth, Quantiles) {
  std::vector<double> v = {0, 1, 2, 3, 4};
  EXPECT_DOUBLE_EQ(quantile(v, 0.5), 2.0);
  EXPECT_DOUBLE_EQ(quantile(v, 0.25), 1.0);
  EXPECT_DOUBLE_EQ(quantile(v, 0.1), 0.4);
  EXPECT_DOUBLE_EQ(quantile(v, 1.0), 4.0);
  EXPECT_DOUBLE_EQ(quantile({}, 0.5), 0.0);
}

// Leaves uniform in a ball of radius R: P(depth ≤ t) = 1 − (1 − t/R)³, so the quartiles are
// R(1 − 0.75^⅓), R(1 − 0.5^⅓) ≈ 0.206 R and R(1 − 0.25^⅓); the histogram's bins likewise.
// The hull of n points lies inside the ball, by about R/√n at its vertices and more at its
// faces' centres (≈ 0.5 % of R here), so every depth is a little smaller.
TEST(CrownDepth, UniformBallHasTheKnownDistribution) {
  const float R = 3.0f;
  const glm::vec3 centre(0.0f, 8.0f, 0.0f);
  Rng rng(17);
  std::vector<glm::vec3> p;
  for (int i = 0; i < 100000; ++i) p.push_back(in_ball(rng, R) + centre);
  // Each depth against the exact ball: never deeper than R − |p|, and shallower by at most
  // the hull's largest gap to the ball, R minus its closest face plane.
  ConvexHull hull = convex_hull(p);
  double sag = 0.0;
  for (const HullPlane& h : hull.planes) sag = std::max(sag, double(R) - (h.offset - glm::dot(h.normal, glm::dvec3(centre))));
  EXPECT_LT(sag, 0.05 * R);
  std::vector<double> depth = depths_below_hull(p);
  for (size_t i = 0; i < p.size(); i += 7) {
    double exact = double(R) - glm::length(glm::dvec3(p[i] - centre));
    ASSERT_LE(depth[i], exact + 1e-5) << i;
    ASSERT_GE(depth[i], exact - sag - 1e-5) << i;
  }
  CrownDepth c = measure_crown_depth(leaves_at(p));
  EXPECT_EQ(c.leaves, 100000u);
  EXPECT_TRUE(c.solid);
  EXPECT_NEAR(c.half_width, R, 0.02f * R);
  EXPECT_NEAR(c.median, R * (1.0f - std::cbrt(0.5f)), 0.01f * R);
  EXPECT_NEAR(c.q1, R * (1.0f - std::cbrt(0.75f)), 0.01f * R);
  EXPECT_NEAR(c.q3, R * (1.0f - std::cbrt(0.25f)), 0.01f * R);
  EXPECT_NEAR(c.median_rel, 1.0f - std::cbrt(0.5f), 0.012f);
  EXPECT_NEAR(c.median_rel, c.median / c.half_width, 1e-6f);
  float sum = 0.0f;
  for (size_t i = 0; i < kCrownDepthBins; ++i) {
    double a = double(i) / kCrownDepthBins, b = double(i + 1) / kCrownDepthBins;
    double expected = std::pow(1.0 - a, 3.0) - std::pow(1.0 - b, 3.0);
    EXPECT_NEAR(c.histogram[i], expected, 0.012) << "bin " << i;
    sum += c.histogram[i];
  }
  EXPECT_NEAR(sum, 1.0f, 1e-5f);
}

// A thin shell (leaves only at the crown's surface) is shallow; the same count filling the
// ball is deep.
TEST(CrownDepth, ShellIsShallowerThanBall) {
  Rng rng(2);
  std::vector<glm::vec3> shell, ball;
  for (int i = 0; i < 4000; ++i) {
    shell.push_back(on_sphere(rng) * float(rng.uniform(4.6, 5.0)));
    ball.push_back(in_ball(rng, 5.0f));
  }
  CrownDepth s = measure_crown_depth(leaves_at(shell)), b = measure_crown_depth(leaves_at(ball));
  EXPECT_LT(s.q3, 0.45f);
  EXPECT_GT(b.median, 0.8f);  // ≈ 0.206 × 5 m, less the hull's gap to the ball at 4000 points
  EXPECT_GT(s.histogram[0], 0.99f);
}

TEST(CrownDepth, NoLeavesOrFlatLeaves) {
  CrownDepth none = measure_crown_depth({});
  EXPECT_EQ(none.leaves, 0u);
  EXPECT_FLOAT_EQ(none.median, 0.0f);
  EXPECT_FLOAT_EQ(none.histogram[0], 0.0f);
  std::vector<glm::vec3> sheet;
  for (int i = 0; i < 100; ++i) sheet.push_back({float(i % 10), float(i / 10), 0.0f});
  CrownDepth flat = measure_crown_depth(leaves_at(sheet));
  EXPECT_FALSE(flat.solid);
  EXPECT_FLOAT_EQ(flat.q3, 0.0f);
  EXPECT_FLOAT_EQ(flat.histogram[0], 1.0f);
}

TEST(ConvexHull2d, CornersOnlyCounterClockwise) {
  // A square with points inside, on its edges and repeated: the hull is its 4 corners, CCW
  // from the lowest-leftmost; exact on integers, the same on doubles.
  std::vector<glm::i64vec2> p{{0, 0}, {4, 0}, {4, 4}, {0, 4}, {2, 0}, {4, 2}, {1, 1}, {2, 3}, {0, 0}, {4, 4}, {0, 2}};
  std::vector<glm::i64vec2> h = convex_hull_2d(p);
  ASSERT_EQ(h.size(), 4u);
  EXPECT_EQ(h[0], glm::i64vec2(0, 0));
  EXPECT_EQ(h[1], glm::i64vec2(4, 0));
  EXPECT_EQ(h[2], glm::i64vec2(4, 4));
  EXPECT_EQ(h[3], glm::i64vec2(0, 4));
  std::vector<glm::dvec2> d;
  for (glm::i64vec2 q : p) d.push_back(glm::dvec2(q) * 0.5);
  std::vector<glm::dvec2> hd = convex_hull_2d(d);
  ASSERT_EQ(hd.size(), 4u);
  EXPECT_EQ(hd[2], glm::dvec2(2.0, 2.0));
  EXPECT_EQ(convex_hull_2d(std::vector<glm::dvec2>{{1, 1}, {1, 1}}).size(), 1u);
}
