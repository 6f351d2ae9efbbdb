// Leaf coverage measured with the engine (engine/tools/measure/leaf_coverage.h) on models
// built in code whose answers are known: a dense sheet of leaves facing the camera covers its
// hull, a checkerboard of leaves half of it, a few tiny leaves in a big box almost none; the
// bark is not drawn and the views are orthographic.
#include <gtest/gtest.h>

#include <algorithm>

#include "engine/tools/measure/leaf_coverage.h"
#include "generators/core/rng.h"
#include "generators/mesh/mesher.h"
#include "tests/gpu/validated_gpu_test.h"

using namespace forest;

namespace {

// A square untextured (opaque) card: x in [−0.5, 0.5], blade y in [0, 1], normal +Z.
Mesh square_card() {
  Mesh m;
  m.vertices = {{{-0.5f, 0.0f, 0.0f}, {0, 0, 1}, {0, 1}},
                {{0.5f, 0.0f, 0.0f}, {0, 0, 1}, {1, 1}},
                {{0.5f, 1.0f, 0.0f}, {0, 0, 1}, {1, 0}},
                {{-0.5f, 1.0f, 0.0f}, {0, 0, 1}, {0, 0}}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

TreeModel model_of(std::vector<LeafPlacement> leaves) {
  TreeModel m;
  m.leaf_card = square_card();
  m.leaves = std::move(leaves);
  // A small bark triangle at the base (a model needs a branch mesh); never drawn here.
  m.branches.vertices = {{{0, 0, 0}, {0, 0, -1}, {}}, {{0.1f, 0, 0}, {0, 0, -1}, {}}, {{0, 0.1f, 0}, {0, 0, -1}, {}}};
  m.branches.indices = {0, 1, 2};
  m.bounding_sphere = bounding_sphere(m.branches, m.leaf_card, m.leaves);
  return m;
}

LeafPlacement leaf_at(glm::vec3 p, float scale) {
  LeafPlacement l;
  l.position = p;
  l.scale = scale;
  return l;
}

// n × n cards of side `cell` in the plane z = 0 (facing the 0° and 180° views), the cell
// (i, j) filled when keep(i, j); overlapping by `overlap` so a full sheet has no seams.
template <typename Keep>
std::vector<LeafPlacement> sheet(int n, float cell, float overlap, Keep keep) {
  std::vector<LeafPlacement> out;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      if (keep(i, j)) {
        LeafPlacement l = leaf_at({(float(i) + 0.5f) * cell, 1.0f + float(j) * cell - 0.5f * overlap, 0.0f}, cell + overlap);
        out.push_back(l);
      }
  return out;
}

class LeafCoverageTest : public ValidatedGpuTest {
 protected:
  LeafCoverage measure(const TreeModel& m, uint32_t resolution = 256) {
    LeafCoverageOptions o;
    o.resolution = resolution;
    o.keep_masks = true;
    return measure_leaf_coverage(ctx_, m, o);
  }
};

void expect_min_is_smallest(const LeafCoverage& c) {
  ASSERT_EQ(c.views.size(), 4u);
  double smallest = 1.0;
  for (const ViewCoverage& v : c.views) {
    EXPECT_LE(c.min, v.mask.coverage());
    smallest = std::min(smallest, v.mask.coverage());
  }
  EXPECT_DOUBLE_EQ(c.min, smallest);
}

}  // namespace

TEST_F(LeafCoverageTest, DenseSheetFacingTheCameraCoversItsHull) {
  LeafCoverage c = measure(model_of(sheet(12, 0.5f, 0.05f, [](int, int) { return true; })));
  expect_min_is_smallest(c);
  EXPECT_FLOAT_EQ(c.views[0].azimuth_deg, 0.0f);
  EXPECT_GT(c.views[0].mask.coverage(), 0.98);  // from −z
  EXPECT_GT(c.views[2].mask.coverage(), 0.98);  // from +z, the back of the cards
  // Face on, the sheet fills the fitted frame: its taller side spans 1 / 1.02 of it.
  EXPECT_GT(double(c.views[0].mask.pixels), 0.85 * 256.0 * 256.0);
  EXPECT_LE(c.min, c.views[1].mask.coverage());  // edge-on from ±x: a sliver, if anything
}

TEST_F(LeafCoverageTest, CheckerboardCoversHalf) {
  // 9 × 9 cells, corners filled: 41 of the 81 cells of the hull's square. Each card is drawn as
  // one triangle of twice its area (engine/render/leaf_card.h); without the fragment shaders'
  // cut back to the quad (leaf_inside_card) the cells overlap and this fails, as does
  // BarkIsNotDrawn (0.87).
  LeafCoverage c = measure(model_of(sheet(9, 0.5f, 0.0f, [](int i, int j) { return (i + j) % 2 == 0; })), 512);
  // Tight: the last leaves drawn (the top row) shrunk by a transition band give 0.495.
  EXPECT_NEAR(c.views[0].mask.coverage(), 41.0 / 81.0, 0.003);
  EXPECT_NEAR(c.views[2].mask.coverage(), 41.0 / 81.0, 0.003);
  expect_min_is_smallest(c);
}

TEST_F(LeafCoverageTest, FewTinyLeavesInABigBoxCoverAlmostNothing) {
  Rng rng(4);
  std::vector<LeafPlacement> leaves;
  for (int i = 0; i < 200; ++i) {
    leaves.push_back(leaf_at({float(rng.uniform(-5, 5)), float(rng.uniform(1, 11)), float(rng.uniform(-5, 5))}, 0.03f));
    // Turned every way, so that no view sees them all edge-on.
    glm::vec3 axis = glm::normalize(glm::vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)) + 1e-3f);
    leaves.back().rotation = glm::angleAxis(float(rng.uniform(0.0, 6.283)), axis);
  }
  LeafCoverage c = measure(model_of(leaves));
  expect_min_is_smallest(c);
  for (const ViewCoverage& v : c.views) {
    EXPECT_GT(v.mask.pixels, 0u) << v.azimuth_deg;
    EXPECT_LT(v.mask.coverage(), 0.02) << v.azimuth_deg;
  }
}

// The bark is not drawn: a 3 × 1 m strip of leaves (y from 1 to 2 m) framed in a square
// view, with a bark triangle (both windings) in the empty frame above it, which would
// stretch the hull of the covered pixels and cut the coverage to about 0.6.
TEST_F(LeafCoverageTest, BarkIsNotDrawn) {
  TreeModel m = model_of(sheet(6, 0.5f, 0.05f, [](int, int j) { return j < 2; }));
  m.branches.vertices = {{{0.2f, 2.4f, 0}, {0, 0, -1}, {}}, {{2.8f, 2.4f, 0}, {0, 0, -1}, {}}, {{1.5f, 3.0f, 0}, {0, 0, -1}, {}}};
  m.branches.indices = {0, 1, 2, 0, 2, 1};
  m.bounding_sphere = bounding_sphere(m.branches, m.leaf_card, m.leaves);
  LeafCoverage c = measure(m);
  EXPECT_GT(c.views[0].mask.coverage(), 0.98);
}

// Orthographic: two equal sheets, one 6 m behind the other and beside it, cover equal pixels.
TEST_F(LeafCoverageTest, ViewsAreOrthographic) {
  std::vector<LeafPlacement> leaves = sheet(4, 0.5f, 0.05f, [](int, int) { return true; });
  for (LeafPlacement l : sheet(4, 0.5f, 0.05f, [](int, int) { return true; })) {
    l.position += glm::vec3(3.0f, 0.0f, 6.0f);
    leaves.push_back(l);
  }
  LeafCoverage c = measure(model_of(leaves));
  const FrameImage& f = c.masks[0];
  uint64_t left = 0, right = 0;
  for (uint32_t y = 0; y < f.height; ++y)
    for (uint32_t x = 0; x < f.width; ++x)
      if (f.pixel(x, y)[0] >= 128) ++(x < f.width / 2 ? left : right);
  ASSERT_GT(left, 1000u);
  EXPECT_NEAR(double(left) / double(right), 1.0, 0.02);
}

TEST_F(LeafCoverageTest, NoLeavesNoCoverage) {
  LeafCoverage c = measure(model_of({}), 64);
  for (const ViewCoverage& v : c.views) EXPECT_EQ(v.mask.pixels, 0u);
  EXPECT_DOUBLE_EQ(c.min, 0.0);
}
