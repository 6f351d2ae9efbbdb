// Visual hull (seed 003): exact hull of pixel masks, reprojection IoU, volume monotonicity,
// skeleton, growth inside the hull, determinism and bad inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <cstring>
#include <fstream>
#include <limits>
#include <set>

#include "generators/common/input_error.h"
#include "generators/common/toml_reader.h"
#include "generators/methods/image_synthetic.h"
#include "generators/methods/image_tree_util.h"
#include "generators/methods/methods.h"
#include "generators/methods/visual_hull_growth.h"

using namespace forest;
namespace fs = std::filesystem;

namespace {

CrownSpec lobes(int views, int resolution, bool perspective) {
  CrownSpec s;
  s.shape = "lobes";
  s.height = 8.0;
  s.width = 7.0;
  s.views = views;
  s.resolution = resolution;
  s.perspective = perspective;
  return s;
}

// Two orthographic views (front, side) of a sphere of radius r.
ViewSet sphere_views(double r, int resolution) {
  SyntheticTree tree;
  tree.parts.push_back({CrownPrimitive::Kind::Ellipsoid, {0, 0, 0}, {r, r, r}, 0});
  tree.bounds = {{-1.2 * r, -1.2 * r, -1.2 * r}, {1.2 * r, 1.2 * r, 1.2 * r}};
  ViewSet set;
  set.bounds = tree.bounds;
  for (glm::dvec3 dir : {glm::dvec3(0, 0, -1), glm::dvec3(-1, 0, 0)}) {
    View v;
    v.camera = orthographic_camera(resolution, resolution, {0, 0, 0}, dir, {0, 1, 0}, 2.4 * r);
    v.mask = render_mask(tree, v.camera);
    set.views.push_back(v);
  }
  return set;
}

}  // namespace

TEST(VisualHull, TwoViewsOfASphereGiveTheSteinmetzSolid) {
  const double r = 2.0;
  ViewSet set = sphere_views(r, 200);
  double v = hull_volume(set, 160);
  EXPECT_NEAR(v, 16.0 * r * r * r / 3.0, 0.015 * 16.0 * r * r * r / 3.0);
  EXPECT_TRUE(inside_hull(set, {0.9 * r, 0.9 * r, 0.0}) == false);  // outside the front disc
  EXPECT_TRUE(inside_hull(set, {0.6 * r, 0.0, 0.6 * r}));          // in both discs, not the sphere
}

TEST(VisualHull, ReprojectionIoUAtLeast099) {
  for (bool perspective : {false, true}) {
    ViewSet set = synthesize_view_set(lobes(perspective ? 8 : 4, 128, perspective));
    for (size_t v = 0; v < set.views.size(); ++v) {
      double iou = reprojection_iou(set, v);
      EXPECT_GE(iou, 0.99) << "view " << v << (perspective ? " perspective" : " orthographic");
    }
  }
}

TEST(VisualHull, VolumeNeverGrowsWithMoreViews) {
  ViewSet all = synthesize_view_set(lobes(8, 96, true));
  ViewSet some = all;
  some.views.clear();
  double previous = std::numeric_limits<double>::infinity();
  for (const View& v : all.views) {
    some.views.push_back(v);
    double vol = hull_volume(some, 80);
    EXPECT_LE(vol, previous + 1e-9);
    previous = vol;
  }
  // And the hull contains the object it was carved from (points well inside the primitives).
  SyntheticTree tree = make_synthetic_tree(lobes(8, 96, true));
  for (const CrownPrimitive& p : tree.parts) {
    if (p.kind != CrownPrimitive::Kind::Ellipsoid) continue;
    for (glm::dvec3 d : {glm::dvec3(0.7, 0, 0), glm::dvec3(0, -0.7, 0), glm::dvec3(0, 0.5, 0.5), glm::dvec3(0, 0, 0)})
      EXPECT_TRUE(inside_hull(all, p.center + d * p.radii));
  }
}

TEST(VisualHull, SegmentTestIsExactOnAConcaveSilhouette) {
  // Front view only: a U-shaped mask; a segment across the notch leaves the hull.
  Mask m;
  m.width = m.height = 30;
  m.alpha.assign(900, 0.0f);
  for (int j = 5; j < 25; ++j)
    for (int i = 5; i < 25; ++i)
      if (i < 12 || i >= 18 || j >= 18) m.alpha[size_t(j * 30 + i)] = 1.0f;
  ViewSet set;
  set.bounds = {{-1.5, -1.5, -1.5}, {1.5, 1.5, 1.5}};
  set.views.push_back({m, orthographic_camera(30, 30, {0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 3.0), {}});
  // Pixel i spans x in [-1.5 + 0.1 i, ...); rows j >= 18 are y <= -0.3.
  glm::dvec3 left(-0.6, 0.5, 0.0), right(0.6, 0.5, 0.0);
  EXPECT_TRUE(inside_hull(set, left));
  EXPECT_TRUE(inside_hull(set, right));
  EXPECT_FALSE(segment_inside_hull(set, left, right));
  double s = inside_fraction(set, left, right);  // leaves at x = -0.3 (pixel 12)
  EXPECT_NEAR(-0.6 + s * 1.2, -0.3, 1e-9);
  EXPECT_TRUE(segment_inside_hull(set, {-0.6, -0.6, 0.0}, {0.6, -0.6, 0.0}));
}

TEST(VisualHull, InterestingPointsSitOnTheLobes) {
  Mask m;
  m.width = m.height = 128;
  m.alpha.assign(size_t(128 * 128), 0.0f);
  std::vector<glm::dvec2> lobe;
  for (int k = 0; k < 5; ++k) {
    double a = glm::radians(90.0 + 72.0 * k);
    lobe.push_back({64 + 40 * std::cos(a), 64 - 40 * std::sin(a)});
  }
  for (int j = 0; j < 128; ++j)
    for (int i = 0; i < 128; ++i) {
      glm::dvec2 p(i + 0.5, j + 0.5);
      bool in = glm::length(p - glm::dvec2(64, 64)) < 22;
      for (glm::dvec2 c : lobe) in = in || glm::length(p - c) < 11;
      if (in) m.alpha[size_t(j * 128 + i)] = 1.0f;
    }
  auto tips = interesting_points(m, 5, 0.08);
  ASSERT_EQ(tips.size(), 5u);
  std::set<int> lobes_hit;
  for (glm::dvec2 t : tips) {
    int nearest = -1;
    for (int k = 0; k < 5; ++k)
      if (glm::length(t - lobe[size_t(k)]) <= 11.5) nearest = k;
    EXPECT_GE(nearest, 0) << t.x << " " << t.y;
    lobes_hit.insert(nearest);
  }
  EXPECT_GE(lobes_hit.size(), 3u);
}

TEST(VisualHull, SkeletonIsOneTreeInsideTheHullKeepingMarkedNodes) {
  ViewSet set = synthesize_view_set(lobes(8, 128, true));
  VoxelGrid grid = voxelize_hull(set, 40);
  HullSkeleton sk = hull_skeleton(set, grid, SkeletonParams{});
  ASSERT_GT(sk.graph.nodes.size(), 10u);
  EXPECT_TRUE(is_rooted_tree(sk.graph));  // connected and acyclic: parent < child, one root
  EXPECT_GE(sk.marked.size(), 4u);
  EXPECT_EQ(sk.marked.front(), 0u);  // the base
  auto children = children_of(sk.graph);
  size_t tips = 0;
  for (uint32_t m : sk.marked) tips += m != 0 && children[m].empty();
  EXPECT_GE(tips, 3u);  // marked tips are skeleton tips
  for (size_t i = 1; i < sk.graph.nodes.size(); ++i)
    EXPECT_TRUE(segment_inside_hull(set, glm::dvec3(sk.graph.nodes[size_t(sk.graph.nodes[i].parent)].position),
                                    glm::dvec3(sk.graph.nodes[i].position)));
  // The base is at the foot of the tree.
  EXPECT_LT(sk.graph.nodes[0].position.y, 0.5f);
}

TEST(VisualHull, GrowthStaysInsideRegrowsShorterAndConservesFlow) {
  ViewSet set = synthesize_view_set(lobes(8, 128, true));
  VoxelGrid grid = voxelize_hull(set, 40);
  HullSkeleton sk = hull_skeleton(set, grid, SkeletonParams{});
  GrowthParams gp;
  gp.internode = 0.35;
  gp.min_length = 0.05;
  gp.years = 5;
  gp.fill_target = 1.1;  // run every year
  GrowthState state = start_growth(sk, gp);
  std::vector<double> lengths;
  for (const Bud& b : state.buds) lengths.push_back(b.length);
  Rng rng(7, 21);
  size_t pruned = 0, grown = 0;
  for (int y = 0; y < gp.years; ++y) {
    YearReport r = grow_year(state, set, grid, gp, rng);
    pruned += r.pruned;
    grown += r.grown;
    // No live segment outside the hull after this iteration.
    for (size_t k = 1; k < state.pos.size(); ++k)
      if (state.alive[k]) ASSERT_TRUE(segment_inside_hull(set, state.pos[size_t(state.parent[k])], state.pos[k])) << "year " << y;
    // Basipetal flow conserved: the base receives the light of every bud.
    EXPECT_NEAR(r.root_flow, r.bud_light, 1e-9 * std::max(1.0, r.bud_light));
    // A pruned bud regrows factor x the pruned length.
    for (auto [bud, len] : r.regrowth) EXPECT_NEAR(len, gp.regrow_factor * lengths[bud], 1e-12);
    lengths.clear();
    for (const Bud& b : state.buds) lengths.push_back(b.length);
  }
  EXPECT_GT(grown, 50u);
  EXPECT_GT(pruned, 0u);  // the boundary was reached and enforced
  TreeGraph g = growth_graph(state);
  EXPECT_TRUE(is_rooted_tree(g));
}

TEST(VisualHull, DefaultPresetIsDeterministic) {
  std::string text = default_species_text("visual-hull");
  TreeModel a = generate_from_species_text(text, "vh.toml");
  TreeModel b = generate_from_species_text(text, "vh.toml");
  ASSERT_GT(a.branches.vertices.size(), 0u);
  EXPECT_GT(a.leaves.size(), 100u);
  EXPECT_EQ(a.meta.dump(), b.meta.dump());
  ASSERT_EQ(a.branches.vertices.size(), b.branches.vertices.size());
  EXPECT_EQ(0, std::memcmp(a.branches.vertices.data(), b.branches.vertices.data(),
                           a.branches.vertices.size() * sizeof(a.branches.vertices[0])));
  EXPECT_EQ(a.branches.indices, b.branches.indices);
  GenerateOptions other;
  other.seed = 99;
  TreeModel c = generate_from_species_text(text, "vh.toml", other);
  EXPECT_NE(c.meta["node_count"], a.meta["node_count"]);
}

TEST(VisualHull, BadInputsNameFileAndKey) {
  fs::path d = fs::temp_directory_path() / ("forest_vh_bad_" + std::to_string(::getpid()));
  fs::create_directories(d);
  std::ofstream(d / "s.toml") << "method = \"visual-hull\"\nviews = \"nope/views.json\"\n";
  try {
    generate_from_species(d / "s.toml");
    ADD_FAILURE();
  } catch (const InputError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("s.toml:2"), std::string::npos) << msg;
    EXPECT_NE(msg.find("views"), std::string::npos) << msg;
  }
  std::ofstream(d / "t.toml") << "method = \"visual-hull\"\ncrown = { shape = \"cube\" }\n";
  EXPECT_THROW(generate_from_species(d / "t.toml"), InputError);
  std::ofstream(d / "u.toml") << "method = \"visual-hull\"\ncrown = { views = 0 }\n";
  try {
    generate_from_species(d / "u.toml");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("crown.views"), std::string::npos) << e.what();
  }
  fs::remove_all(d);
}
