// Method silhouettes (Wither 2009): bumps, BAF, Hermite branches, span transfer, sub-silhouettes,
// fill-in, Gibbs placement, generation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "generators/asset/asset_io.h"
#include "generators/core/input_error.h"
#include "generators/core/rng.h"
#include "generators/species/registry.h"
#include "generators/methods/silhouettes/silhouettes_method.h"
#include "generators/methods/silhouettes/silhouettes_placement.h"
#include "generators/methods/silhouettes/silhouettes_style.h"

using namespace forest;

namespace {

Polygon2 round_silhouette() {
  Drawing d = silhouettes_synthetic_drawing("round");
  Polygon2 p = d.strokes[1].points;
  p.pop_back();
  return p;
}

}  // namespace

TEST(Silhouettes, FiveBumpsEachInsideItsDisc) {
  std::vector<Bump> bumps = silhouette_bumps(round_silhouette());
  auto discs = silhouettes_round_discs();
  ASSERT_EQ(bumps.size(), 5u);
  // Bumps are sorted by angle about the centroid, as the discs are (20 ... 160 degrees).
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_LT(glm::length(bumps[i].end - discs[i].first), discs[i].second) << i;
    // The terminal tangent points out of the crown, toward the disc's side.
    EXPECT_GT(glm::dot(bumps[i].tangent, discs[i].first - glm::dvec2(0, 6)), 0.0) << i;
  }
  EXPECT_TRUE(silhouette_bumps({{0, 0}, {1, 1}, {2, 2}}).empty());  // no area, no bumps
}

TEST(Silhouettes, BafIsExactAtEndsAndSamples) {
  auto baf = BranchingAngleFunction::linear(80.0, 30.0);
  EXPECT_DOUBLE_EQ(baf(0.0), 80.0);
  EXPECT_DOUBLE_EQ(baf(1.0), 30.0);
  EXPECT_DOUBLE_EQ(baf(0.5), 55.0);
  baf.add_sample(0.4, 20.0);
  EXPECT_DOUBLE_EQ(baf(0.4), 20.0);
  EXPECT_DOUBLE_EQ(baf(0.2), 50.0);
  EXPECT_DOUBLE_EQ(baf(0.7), 25.0);
  baf.add_sample(0.4, 70.0);  // the same t replaces
  EXPECT_EQ(baf.samples.size(), 3u);
  EXPECT_DOUBLE_EQ(baf(0.4), 70.0);
}

TEST(Silhouettes, HermiteBranchesPassThroughBAndEWithTheirTangents) {
  glm::dvec2 p0(0, 0), m0(1, 2), p1(3, 1), m1(-1, 0.5);
  EXPECT_EQ(hermite(p0, m0, p1, m1, 0.0), p0);
  EXPECT_EQ(hermite(p0, m0, p1, m1, 1.0), p1);
  EXPECT_LT(glm::length(hermite_derivative(p0, m0, p1, m1, 0.0) - m0), 1e-12);
  EXPECT_LT(glm::length(hermite_derivative(p0, m0, p1, m1, 1.0) - m1), 1e-12);

  Polyline2 axis({{0, 0}, {0, 8}});
  auto baf = BranchingAngleFunction::linear(80.0, 30.0);
  Bump bump{{2.8, 6.9}, glm::normalize(glm::dvec2(1, 0.4)), 1.0};
  Branch2D b = infer_branch(axis, bump, baf, 0.3, 32);
  ASSERT_GE(b.curve.size(), 2u);
  EXPECT_LT(glm::length(b.curve.front() - axis.at(b.t)), 1e-12);  // B on the axis
  EXPECT_LT(glm::length(b.curve.back() - bump.end), 1e-12);        // ends at E
  EXPECT_EQ(b.side, 1);                                            // E is right of the trunk
  // Start tangent = the axis tangent turned by BAF(t) toward E; the curve is the Hermite
  // curve with both tangents of length |E - B| / 2.
  double angle = std::acos(glm::dot(b.start_tangent, glm::dvec2(0, 1))) * 180.0 / 3.14159265358979;
  EXPECT_NEAR(angle, baf(b.t), 1e-9);
  EXPECT_GT(b.start_tangent.x, 0.0);
  double span = glm::length(bump.end - b.curve.front());
  for (size_t k = 0; k < b.curve.size(); ++k)
    EXPECT_LT(glm::length(b.curve[k] - hermite(b.curve.front(), b.start_tangent * (0.5 * span), bump.end,
                                               bump.tangent * (0.5 * span), double(k) / (b.curve.size() - 1))),
              1e-12);
  // It is the shortest of the candidates: a branch from any other base is not shorter.
  auto length = [](const std::vector<glm::dvec2>& c) {
    double s = 0;
    for (size_t k = 1; k < c.size(); ++k) s += glm::length(c[k] - c[k - 1]);
    return s;
  };
  Branch2D from_top = infer_branch(axis, bump, baf, 0.99, 2);
  EXPECT_LE(length(b.curve), length(from_top.curve) + 1e-12);
}

TEST(Silhouettes, SpanTransferOntoItselfIsIdentity) {
  std::vector<glm::dvec2> c{{1, 1}, {1.5, 2.2}, {2.5, 2.7}, {4, 2.5}};
  auto same = span_transfer(c, c.front(), c.back());
  for (size_t i = 0; i < c.size(); ++i) EXPECT_LT(glm::length(same[i] - c[i]), 1e-12);
  // Onto a span twice as long and turned: ends land on the target, shape scales by 2.
  auto moved = span_transfer(c, {0, 0}, {0, 2.0 * glm::length(c.back() - c.front())});
  EXPECT_LT(glm::length(moved.front()), 1e-12);
  EXPECT_NEAR(glm::length(moved[1] - moved[0]), 2.0 * glm::length(c[1] - c[0]), 1e-12);
}

TEST(Silhouettes, ConeAngleStaysInRange) {
  double previous = 0.0;
  for (double ratio = 0.0; ratio <= 2.0; ratio += 0.01) {
    double a = sub_silhouette_cone_deg(ratio, 1.0);
    EXPECT_GE(a, 20.0);
    EXPECT_LE(a, 110.0);
    EXPECT_GE(a, previous);  // sharp features narrow, smooth ones wide
    previous = a;
  }
  // A sub-silhouette closes back at the branch base and shares edges with the parent.
  Polygon2 sil = round_silhouette();
  Polygon2 sub = infer_sub_silhouette(sil, {0, 4.5}, {2.8, 6.9}, 1.1);
  ASSERT_GT(sub.size(), 10u);
  double nearest_base = 1e9;
  for (glm::dvec2 p : sub) nearest_base = std::min(nearest_base, glm::length(p - glm::dvec2(0, 4.5)));
  EXPECT_LT(nearest_base, 1e-9);
  EXPECT_GT(polygon_area(sub), 0.5);
  EXPECT_LT(polygon_area(sub), polygon_area(sil));
}

TEST(Silhouettes, FillInOverlapsAtMostTwentyPercent) {
  Polygon2 sil = round_silhouette();
  Polyline2 axis({{0, 0}, {0, 8}});
  auto baf = BranchingAngleFunction::linear(80.0, 30.0);
  std::vector<Branch2D> siblings;
  for (const Bump& b : silhouette_bumps(sil)) {
    Branch2D br = infer_branch(axis, b, baf, 0.45);
    br.crown = infer_sub_silhouette(sil, br.curve.front(), br.curve.back(), b.radius);
    siblings.push_back(br);
  }
  std::vector<Branch2D> added = fill_in(axis, sil, siblings, baf, 0.45, 12, 0.2);
  std::vector<Polygon2> crowns;
  for (const Branch2D& b : siblings) crowns.push_back(b.crown);
  for (const Branch2D& b : added) {
    EXPECT_TRUE(b.filled);
    EXPECT_LE(crown_overlap(b.crown, crowns), 0.2);
    for (glm::dvec2 p : b.curve) EXPECT_TRUE(point_in_polygon(sil, p));
    crowns.push_back(b.crown);
  }
  // A threshold of 0 accepts only copies that overlap nothing; 1 accepts every fitting one.
  EXPECT_LE(fill_in(axis, sil, siblings, baf, 0.45, 12, 0.0).size(), added.size());
  EXPECT_GE(fill_in(axis, sil, siblings, baf, 0.45, 12, 1.0).size(), added.size());
}

TEST(Silhouettes, GibbsEnergyNeverIncreasesAndPointsStayInDomains) {
  for (const char* preset : {"none", "spiral", "decussate", "whorl3"}) {
    BranchPhyllotaxis p;
    ASSERT_TRUE(phyllotaxis_preset(preset, p));
    std::vector<InsertionPoint> pts;
    Rng rng(9);
    for (int i = 0; i < 14; ++i) {
      InsertionPoint q;
      if (i < 4) {  // sketched: fixed u, theta within 45 degrees of its side
        q.u = q.u_min = q.u_max = 1.0 + i;
        double ref = i % 2 ? 180.0 : 0.0;
        q.theta = ref, q.theta_min = ref - 45, q.theta_max = ref + 45;
      } else {
        q.u_min = 0.5, q.u_max = 8.0, q.u = rng.uniform(0.5, 8.0), q.theta = rng.uniform(0, 360);
      }
      pts.push_back(q);
    }
    auto copy = pts;
    GibbsParams g;
    GibbsResult r = place_insertion_points(pts, 8.0, p, g, 77);
    EXPECT_LE(r.iterations, 3000);
    for (size_t k = 1; k < r.energy.size(); ++k) EXPECT_LE(r.energy[k], r.energy[k - 1]) << preset;
    EXPECT_LT(r.energy.back(), r.energy.front()) << preset;
    EXPECT_NEAR(r.energy.back(), gibbs_energy(pts, 8.0, p, g), 1e-6 * r.energy.front());
    for (const InsertionPoint& q : pts) {
      EXPECT_GE(q.u, q.u_min);
      EXPECT_LE(q.u, q.u_max);
      if (q.theta_max - q.theta_min < 360) {
        EXPECT_GE(q.theta, q.theta_min);
        EXPECT_LE(q.theta, q.theta_max);
      }
    }
    place_insertion_points(copy, 8.0, p, g, 77);  // fixed seed, fixed result
    for (size_t i = 0; i < pts.size(); ++i) EXPECT_EQ(copy[i].theta, pts[i].theta);
    for (size_t i = 0; i < pts.size(); ++i)
      for (size_t j = 0; j < pts.size(); ++j) {
        double d = pattern_distance(pts[i], pts[j], 8.0, int(pts.size()), p);
        EXPECT_GE(d, 0.0);
        EXPECT_LE(d, 0.5);
        EXPECT_DOUBLE_EQ(d, pattern_distance(pts[j], pts[i], 8.0, int(pts.size()), p));
      }
  }
  GibbsParams many;
  many.max_iterations = 100000;
  std::vector<InsertionPoint> two(2);
  two[1].u_max = 1.0;
  EXPECT_LE(place_insertion_points(two, 1.0, {}, many, 1).iterations, 3000);
}

TEST(Silhouettes, HierarchyAndModel) {
  SilhouetteParams sp;
  auto h = infer_hierarchy(silhouettes_synthetic_drawing("round"), sp);
  ASSERT_GT(h.size(), 10u);
  EXPECT_GE(h[0].children.size(), 5u);  // one per bump, plus fill-in
  size_t sketched = 0;
  for (int c : h[0].children) sketched += h[size_t(c)].branch.sketched;
  EXPECT_EQ(sketched, 1u);  // the scripted over-sketch replaced one inferred branch
  for (size_t i = 1; i < h.size(); ++i) EXPECT_LT(h[i].parent, int(i));

  std::string text = default_species_text("silhouettes");
  auto bytes = [&](uint64_t seed) { return encode_glb(generate_from_species_text(text, "s.toml", {seed})); };
  EXPECT_EQ(bytes(2), bytes(2));
  EXPECT_NE(bytes(2), bytes(3));
  TreeModel m = generate_from_species_text(text, "s.toml");
  EXPECT_GT(m.leaves.size(), 100u);
  EXPECT_GT(double(m.meta["height"]), 8.0);
  EXPECT_LT(double(m.meta["height"]), 12.0);
}

TEST(Silhouettes, InputErrors) {
  auto fails = [](const std::string& json, const std::string& part) {
    try {
      Drawing d = parse_drawing_json(json, "s.json");
      infer_hierarchy(d, {});
      ADD_FAILURE() << json;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  fails(R"({"strokes": [{"id": "c", "role": "silhouette", "points": [[0, 0], [1, 0], [0, 1]]}]})", "axis");
  fails(R"({"strokes": [{"id": "t", "role": "axis", "points": [[0, 0], [0, 1]]}]})", "silhouette");
  fails(R"({"strokes": [{"id": "t", "role": "axis", "points": [[0, 0], [0, 1]]},
        {"id": "c", "role": "silhouette", "points": [[0, 0], [1, 1], [2, 2]]}]})", "no area");
  fails(R"({"strokes": [{"id": "t", "role": "axis", "points": [[0, 0], [0, 1]]},
        {"id": "c", "role": "crown", "points": [[0, 0], [1, 1], [2, 2]]}]})", "role");
  auto dir = std::filesystem::path(FOREST_SOURCE_DIR) / "scenes" / "species";
  for (const char* name : {"silhouettes_round", "silhouettes_poplar_hero"}) {
    TreeModel m = generate_from_species(dir / (std::string(name) + ".toml"));
    EXPECT_GT(m.leaves.size(), 0u) << name;
  }
}

TEST(Silhouettes, StyleIsMeasuredFromTheChildren) {
  Polyline2 axis(std::vector<glm::dvec2>{{0, 0}, {0, 10}});
  std::vector<Branch2D> kids;
  const double ts[] = {0.2, 0.35, 0.5, 0.65}, deg[] = {80, 70, 60, 50};
  for (int i = 0; i < 4; ++i) {
    Branch2D b;
    b.t = ts[i];
    glm::dvec2 base(0, 10 * ts[i]);
    b.curve = {base, base + rotate({0, 1}, i % 2 ? deg[i] : -deg[i])};  // both sides
    kids.push_back(b);
  }
  std::vector<const Branch2D*> ptr;
  for (const Branch2D& b : kids) ptr.push_back(&b);
  BranchingStyle s = measure_style(axis, ptr);
  EXPECT_EQ(s.children, 4u);
  EXPECT_NEAR(s.unbranched, 0.2, 1e-12);
  EXPECT_NEAR(s.spacing_mean, 0.15, 1e-12);
  EXPECT_NEAR(s.spacing_sd, 0.0, 1e-12);
  EXPECT_NEAR(s.baf(0.35), 70.0, 1e-9);
  EXPECT_NEAR(s.baf(0.425), 65.0, 1e-9);
}

TEST(Silhouettes, StylePositionsFollowTheSourceStatistics) {
  BranchingStyle s;
  s.children = 5;
  s.unbranched = 0.1;
  s.spacing_mean = 0.05;
  s.spacing_sd = 0.01;
  std::vector<double> gaps;
  for (uint64_t seed = 0; seed < 200; ++seed) {
    Rng rng(seed, 3);
    std::vector<double> t = style_positions(s, rng);
    ASSERT_FALSE(t.empty());
    EXPECT_EQ(t.front(), 0.1);  // the unbranched range
    EXPECT_LE(t.back(), 1.0);
    for (size_t i = 1; i < t.size(); ++i) gaps.push_back(t[i] - t[i - 1]);
  }
  double mean = 0.0, var = 0.0;
  for (double g : gaps) mean += g / double(gaps.size());
  for (double g : gaps) var += (g - mean) * (g - mean) / double(gaps.size());
  EXPECT_NEAR(mean, 0.05, 0.0015);
  EXPECT_NEAR(std::sqrt(var), 0.01, 0.0015);
}

TEST(Silhouettes, StyleCopyPlacesSiblingsChildrenByTheSourceStyle) {
  SilhouetteParams sp;
  sp.levels = 2;
  std::vector<SilhouetteNode> h = infer_hierarchy(silhouettes_synthetic_drawing("round"), sp);
  int source = -1;
  for (int c : h[0].children)
    if (h[size_t(c)].branch.sketched) source = c;
  ASSERT_GE(source, 0);
  Polyline2 src_axis(h[size_t(source)].branch.curve);
  std::vector<const Branch2D*> kids;
  for (int c : h[size_t(source)].children) kids.push_back(&h[size_t(c)].branch);
  BranchingStyle style = measure_style(src_axis, kids);
  ASSERT_GE(style.children, 2u);
  Rng rng(5, 1);
  size_t restyled = copy_style(h, source, rng, 100000);
  EXPECT_GE(restyled, 3u);
  size_t checked = 0;
  for (int k : h[0].children) {
    if (k == source || h[size_t(k)].children.empty()) continue;
    Polyline2 axis(h[size_t(k)].branch.curve);
    std::vector<double> ts;
    for (int c : h[size_t(k)].children) {
      const Branch2D& b = h[size_t(c)].branch;
      EXPECT_EQ(h[size_t(c)].parent, k);
      ts.push_back(b.t);
      EXPECT_NEAR(glm::length(b.curve.front() - axis.at(b.t)), 0.0, 1e-9);  // on the target
      // Its start makes the source's BAF with the target's tangent.
      glm::dvec2 d = glm::normalize(b.curve[1] - b.curve[0]), tan = axis.tangent(b.t);
      double angle = std::acos(std::clamp(glm::dot(d, tan), -1.0, 1.0)) * 180.0 / 3.14159265358979323846;
      EXPECT_NEAR(angle, style.baf(b.t), 1e-6);
      ++checked;
    }
    std::sort(ts.begin(), ts.end());
    EXPECT_NEAR(ts.front(), style.unbranched, 1e-12);  // the source's unbranched range
    for (size_t i = 1; i < ts.size(); ++i) EXPECT_GE(ts[i] - ts[i - 1], 0.02 - 1e-12);
  }
  EXPECT_GT(checked, 5u);
}
