// Visual hull (Shlyakhter 2001): exact hull of pixel masks, reprojection IoU, volume monotonicity,
// skeleton, growth inside the hull, determinism and bad inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <cstring>
#include <fstream>
#include <limits>
#include <set>

#include "generators/core/input_error.h"
#include "generators/core/toml_reader.h"
#include "generators/methods/common/image_synthetic.h"
#include "generators/methods/common/image_tree_util.h"
#include "generators/species/registry.h"
#include "generators/methods/visual_hull/visual_hull_growth.h"
#include "generators/methods/visual_hull/voxel_thinning.h"

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

// A mask from a polygon (pixel coordinates, v down): pixel centres inside (even-odd rule).
static Mask polygon_mask(int size, const std::vector<glm::dvec2>& poly) {
  Mask m;
  m.width = m.height = size;
  m.alpha.assign(size_t(size * size), 0.0f);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      glm::dvec2 p(i + 0.5, j + 0.5);
      bool in = false;
      for (size_t k = 0, l = poly.size() - 1; k < poly.size(); l = k++)
        if ((poly[k].y > p.y) != (poly[l].y > p.y) &&
            p.x < poly[l].x + (poly[k].x - poly[l].x) * (p.y - poly[l].y) / (poly[k].y - poly[l].y))
          in = !in;
      if (in) m.alpha[size_t(j * size + i)] = 1.0f;
    }
  return m;
}

TEST(VisualHull, OutlineIsTracedInOrderAroundTheLargestComponent) {
  Mask m = polygon_mask(40, {{5, 5}, {25, 5}, {25, 30}, {5, 30}});  // 20 x 25 pixels
  m.alpha[size_t(38 * 40 + 38)] = 1.0f;                               // a stray pixel elsewhere
  auto outline = trace_outline(m);
  ASSERT_EQ(outline.size(), size_t(2 * (20 + 25) - 4));  // every rim pixel once
  for (size_t k = 0; k < outline.size(); ++k) {
    glm::dvec2 step = outline[(k + 1) % outline.size()] - outline[k];
    EXPECT_LE(std::max(std::abs(step.x), std::abs(step.y)), 1.0) << k;  // 8-connected, closed
    EXPECT_LT(outline[k].x, 26.0);
  }
}

TEST(VisualHull, OutlineTipsAreExactlyTheLobesBetweenPockets) {
  // A disc with five lobes: five pockets of the hull, one tip per lobe, nothing else.
  Mask m;
  m.width = m.height = 128;
  m.alpha.assign(size_t(128 * 128), 0.0f);
  std::vector<glm::dvec2> lobe;
  for (int k = 0; k < 5; ++k) {
    double a = glm::radians(90.0 + 72.0 * k);
    lobe.push_back({64 + 30 * std::cos(a), 64 - 30 * std::sin(a)});
  }
  for (int j = 0; j < 128; ++j)
    for (int i = 0; i < 128; ++i) {
      glm::dvec2 p(i + 0.5, j + 0.5);
      bool in = glm::length(p - glm::dvec2(64, 64)) < 22;
      for (glm::dvec2 c : lobe) in = in || glm::length(p - c) < 11;
      if (in) m.alpha[size_t(j * 128 + i)] = 1.0f;
    }
  auto tips = outline_tips(m, OutlineTipParams{});
  ASSERT_EQ(tips.size(), 5u);
  std::set<int> lobes_hit;
  for (const OutlineTip& t : tips) {
    EXPECT_EQ(t.level, 0);
    EXPECT_GT(t.depth, 5.0);  // it sits between real pockets
    for (int k = 0; k < 5; ++k) {
      glm::dvec2 outward = glm::normalize(lobe[size_t(k)] - glm::dvec2(64, 64));
      // On the lobe's outer rim: within a pixel of radius 11 around the lobe centre, outward.
      if (glm::length(t.pixel - lobe[size_t(k)]) <= 12.0 && glm::dot(t.pixel - lobe[size_t(k)], outward) > 8.0)
        lobes_hit.insert(k);
    }
  }
  EXPECT_EQ(lobes_hit.size(), 5u);
}

TEST(VisualHull, OutlineTipsRecurseIntoDeepPockets) {
  // Two tall pointed lobes with a deep notch between them and a short lobe standing in the
  // notch; flat bottom holding the trunk foot. Level 0 gives the two tall apexes, the notch
  // (a deep pocket) holds the short lobe: its apex is a level-2 tip. The bottom corners are
  // the ends of the hull edge at the foot: no tips.
  Mask m = polygon_mask(128, {{20, 10}, {40, 90}, {56, 90}, {64, 50}, {72, 90}, {88, 90}, {108, 10},
                              {118, 118}, {10, 118}});
  auto tips = outline_tips(m, OutlineTipParams{}, glm::dvec2(64, 118));
  ASSERT_EQ(tips.size(), 3u);
  // Pixel centres inside the pointed apexes lie a few pixels below the polygon's corners.
  auto near = [](glm::dvec2 a, glm::dvec2 b) { return glm::length(a - b) < 5.0; };
  EXPECT_EQ(tips[0].level, 0);
  EXPECT_EQ(tips[1].level, 0);
  EXPECT_TRUE((near(tips[0].pixel, {20, 10.5}) && near(tips[1].pixel, {108, 10.5})) ||
              (near(tips[1].pixel, {20, 10.5}) && near(tips[0].pixel, {108, 10.5})))
      << tips[0].pixel.x << "," << tips[0].pixel.y << " " << tips[1].pixel.x << "," << tips[1].pixel.y;
  EXPECT_EQ(tips[2].level, 2);
  EXPECT_TRUE(near(tips[2].pixel, {64, 51})) << tips[2].pixel.x << "," << tips[2].pixel.y;
  EXPECT_NEAR(tips[2].depth, 40.0, 3.0);  // the short lobe's height above the notch floor
  // Without recursion the notch lobe is not found; a convex blob has a single tip, the point
  // farthest from the foot.
  OutlineTipParams flat;
  flat.max_level = 0;
  EXPECT_EQ(outline_tips(m, flat, glm::dvec2(64, 118)).size(), 2u);
  Mask blob;
  blob.width = blob.height = 64;
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i)
      blob.alpha.push_back(glm::length((glm::dvec2(i + 0.5, j + 0.5) - glm::dvec2(32, 34)) / glm::dvec2(14, 24)) < 1.0 ? 1.0f : 0.0f);
  auto one = outline_tips(blob, OutlineTipParams{}, glm::dvec2(32, 58));
  ASSERT_EQ(one.size(), 1u);
  EXPECT_LT(one[0].pixel.y, 11.0);
}

TEST(VisualHull, ThinningKeepsAnchorsAndTopologyAlongTheMedialAxis) {
  // A solid box 21 x 9 x 9: thinned with its two end-face centres as anchors, what is left is
  // one simple 26-connected curve between them, on the box's axis where the axis is the
  // medial axis (away from the end faces, whose corners tie in distance).
  VoxelSolid box;
  box.dims = {25, 13, 13};
  box.occupied.assign(size_t(25 * 13 * 13), 0);
  for (int z = 2; z < 11; ++z)
    for (int y = 2; y < 11; ++y)
      for (int x = 2; x < 23; ++x) box.occupied[box.index({x, y, z})] = 1;
  std::vector<double> dt = boundary_distance(box);
  EXPECT_EQ(dt[box.index({12, 6, 6})], 4.0);
  EXPECT_TRUE(is_simple_voxel(box, {2, 2, 2}));  // a corner goes without changing topology
  size_t a = box.index({2, 6, 6}), b = box.index({22, 6, 6});
  VoxelSolid thin = box;
  thin_to_anchors(thin, {a, b}, dt);
  size_t left = 0;
  for (size_t i = 0; i < thin.occupied.size(); ++i) {
    if (!thin.occupied[i]) continue;
    ++left;
    glm::ivec3 c = thin.cell(i);
    int neighbours = 0;
    for (int k = 0; k < 27; ++k) neighbours += k != 13 && thin.at(c + glm::ivec3(k % 3 - 1, k / 3 % 3 - 1, k / 9 - 1));
    EXPECT_EQ(neighbours, i == a || i == b ? 1 : 2) << c.x << " " << c.y << " " << c.z;  // a simple curve
    if (c.x >= 7 && c.x <= 17) {
      EXPECT_EQ(c.y, 6);
      EXPECT_EQ(c.z, 6);
    }
  }
  EXPECT_GE(left, 21u);
  EXPECT_LE(left, 25u);
  // Without anchors a solid shrinks to one voxel (topology of a ball).
  VoxelSolid ball = box;
  thin_to_anchors(ball, {}, dt);
  size_t ones = 0;
  for (uint8_t o : ball.occupied) ones += o;
  EXPECT_EQ(ones, 1u);
}

TEST(VisualHull, SkeletonIsOneTreeInsideTheHullKeepingMarkedNodes) {
  ViewSet set = synthesize_view_set(lobes(8, 128, true));
  VoxelGrid grid = voxelize_hull(set, 40);
  HullSkeleton sk = hull_skeleton(set, grid, SkeletonParams{});
  ASSERT_GT(sk.graph.nodes.size(), 10u);
  EXPECT_TRUE(is_rooted_tree(sk.graph));  // connected and acyclic: parent < child, one root
  EXPECT_GE(sk.marked.size(), 4u);
  EXPECT_EQ(sk.marked.size(), sk.marks);  // every marked voxel is a node
  EXPECT_GT(sk.second_pass, 0u);          // the second pass added a branching level
  EXPECT_EQ(sk.marked.front(), 0u);       // the base
  auto children = children_of(sk.graph);
  std::set<uint32_t> marked(sk.marked.begin(), sk.marked.end());
  size_t tips = 0;
  for (size_t i = 1; i < sk.graph.nodes.size(); ++i)
    if (children[i].empty()) {
      EXPECT_TRUE(marked.count(uint32_t(i))) << "unmarked end " << i;  // thinned away otherwise
      ++tips;
    }
  EXPECT_GE(tips, 3u);
  for (size_t i = 1; i < sk.graph.nodes.size(); ++i)
    EXPECT_TRUE(segment_inside_hull(set, glm::dvec3(sk.graph.nodes[size_t(sk.graph.nodes[i].parent)].position),
                                    glm::dvec3(sk.graph.nodes[i].position)));
  // The base is at the foot of the tree.
  EXPECT_LT(sk.graph.nodes[0].position.y, 0.5f);
  // Inner skeleton nodes run along the medial axis: deeper in the hull than its average voxel.
  VoxelSolid solid{grid.dims, grid.occupied};
  std::vector<double> dt = boundary_distance(solid);
  double hull_mean = 0.0, inner_mean = 0.0;
  size_t hull_count = 0, inner_count = 0;
  for (size_t i = 0; i < dt.size(); ++i)
    if (grid.occupied[i]) hull_mean += dt[i], ++hull_count;
  for (size_t i = 1; i < sk.graph.nodes.size(); ++i) {
    if (children[i].size() != 1 || marked.count(uint32_t(i))) continue;
    glm::ivec3 c(glm::floor((glm::dvec3(sk.graph.nodes[i].position) - grid.origin) / grid.cell));
    inner_mean += dt[solid.index(c)], ++inner_count;
  }
  ASSERT_GT(inner_count, 5u);
  EXPECT_GT(inner_mean / double(inner_count), 1.5 * hull_mean / double(hull_count));
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
      if (state.alive[k]) {
        ASSERT_TRUE(segment_inside_hull(set, state.pos[size_t(state.parent[k])], state.pos[k])) << "year " << y;
      }
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
