// How deep leaves sit below the surface of their crown: for each leaf, the distance from its
// position to the surface of the convex hull of all leaf positions (convex_hull.h, exact up
// to the hull's tolerance), summarized as quartiles and a histogram (`forest measure`). A
// crown of leaves in a thin outer shell has small depths; leaves filling a ball uniformly
// have median depth R (1 − 0.5^(1/3)) ≈ 0.206 R.
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "generators/tree/tree_graph.h"

namespace forest {

inline constexpr size_t kCrownDepthBins = 10;

struct CrownDepth {
  uint32_t leaves = 0;
  // Crown half-width (m): half the mean of the leaf positions' x and z extents, the unit of
  // the relative depths (habit.h's crown_width / 2).
  float half_width = 0;
  float q1 = 0, median = 0, q3 = 0;              // depth quartiles (m)
  float q1_rel = 0, median_rel = 0, q3_rel = 0;  // ÷ half_width (0 when it is 0)
  // Fraction of leaves per bin of depth ÷ half_width: bin i holds [i/10, (i+1)/10), the
  // last also everything deeper. Sums to 1 (all zeros without leaves).
  std::array<float, kCrownDepthBins> histogram{};
  bool solid = false;  // the leaves span a volume; false: every depth is 0
};

CrownDepth measure_crown_depth(std::span<const LeafPlacement> leaves);

// Depth of every point below the convex hull of all of them (m), in input order.
std::vector<double> depths_below_hull(std::span<const glm::vec3> points);

// Quantile q in [0, 1] of ascending `sorted` values, linearly interpolated between ranks
// (0 for none).
double quantile(const std::vector<double>& sorted, double q);

}  // namespace forest
