// Leaf rendering priority (Neubert 2012 §7.3): random, density, orientation, combined orders.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <tuple>

#include "generators/bake/hull/hull.h"
#include "generators/bake/priority/priority.h"
#include "generators/bake/priority/priority_stratify.h"
#include "generators/core/input_error.h"
#include "generators/core/rng.h"

using namespace forest;

namespace {

// A card whose normal (+Z) is `n`.
glm::quat facing(glm::vec3 n, Rng& rng) {
  glm::vec3 up = std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  glm::vec3 y = glm::normalize(glm::cross(n, glm::cross(up, n)));
  float a = float(rng.uniform(0.0, 6.283185307));
  y = glm::normalize(std::cos(a) * y + std::sin(a) * glm::cross(n, y));  // random spin about n
  glm::vec3 x = glm::cross(y, n);
  return glm::quat_cast(glm::mat3(x, y, n));
}

struct Crown {
  TreeModel model;
  std::vector<bool> radial;  // leaf faces along the crown's radius (parallel to its hull)
};

// Leaves in a sphere of radius 1 around (0, 3, 0), generated bottom to top (index order
// correlates with height). Half face radially, half tangentially.
Crown sphere_crown(size_t n, uint64_t seed) {
  Rng rng(seed, 1);
  std::vector<std::pair<float, LeafPlacement>> tmp;
  std::vector<bool> radial_tmp;
  Crown c;
  for (size_t i = 0; i < n; ++i) {
    glm::vec3 p;
    do p = glm::vec3(rng.symmetric(), rng.symmetric(), rng.symmetric());
    while (glm::dot(p, p) > 1.0f || glm::dot(p, p) < 0.04f);
    glm::vec3 radial_dir = glm::normalize(p);
    bool radial = (i % 2) == 0;
    glm::vec3 t = glm::normalize(glm::cross(radial_dir, glm::vec3(0.3f, 0.9f, 0.1f)));
    LeafPlacement l;
    l.scale = 0.02f;
    l.rotation = facing(radial ? radial_dir : t, rng);
    // Place so that the card's centre is at p.
    l.position = glm::vec3(0, 3, 0) + p - l.rotation * glm::vec3(0, 0.5f * l.scale, 0);
    tmp.push_back({l.position.y, l});
    radial_tmp.push_back(radial);
  }
  std::vector<size_t> idx(n);
  std::iota(idx.begin(), idx.end(), 0);
  std::sort(idx.begin(), idx.end(), [&](size_t a, size_t b) { return tmp[a].first < tmp[b].first; });
  for (size_t i : idx) c.model.leaves.push_back(tmp[i].second), c.radial.push_back(radial_tmp[i]);
  return c;
}

// The sparse crown of sphere_crown(3000, 6) with a dense clump of 1500 leaves inside
// (indices 3000 and up, not radial).
Crown clumped_crown() {
  Crown c = sphere_crown(3000, 6);
  Rng rng(6, 2);
  for (int i = 0; i < 1500; ++i) {
    LeafPlacement l;
    l.scale = 0.02f;
    l.position = glm::vec3(0.4f, 3.3f, 0.1f) + 0.18f * glm::vec3(rng.symmetric(), rng.symmetric(), rng.symmetric());
    c.model.leaves.push_back(l);
    c.radial.push_back(false);
  }
  return c;
}

bool is_permutation(const std::vector<uint32_t>& order, size_t n) {
  if (order.size() != n) return false;
  std::vector<bool> seen(n, false);
  for (uint32_t i : order) {
    if (i >= n || seen[i]) return false;
    seen[i] = true;
  }
  return true;
}

// Spearman rank correlation between survival rank and a per-leaf value.
double rank_correlation(const std::vector<uint32_t>& order, const std::vector<double>& value) {
  const size_t n = order.size();
  std::vector<double> rank_a(n), rank_b(n);
  for (size_t r = 0; r < n; ++r) rank_a[order[r]] = double(r);
  std::vector<size_t> idx(n);
  std::iota(idx.begin(), idx.end(), 0);
  std::sort(idx.begin(), idx.end(), [&](size_t a, size_t b) { return value[a] < value[b]; });
  for (size_t r = 0; r < n; ++r) rank_b[idx[r]] = double(r);
  double ma = (n - 1) / 2.0, sab = 0, saa = 0, sbb = 0;
  for (size_t i = 0; i < n; ++i) {
    sab += (rank_a[i] - ma) * (rank_b[i] - ma);
    saa += (rank_a[i] - ma) * (rank_a[i] - ma);
    sbb += (rank_b[i] - ma) * (rank_b[i] - ma);
  }
  return sab / std::sqrt(saa * sbb);
}

template <class F>
double mean_over(const std::vector<uint32_t>& order, size_t begin, size_t end, F&& f) {
  double s = 0.0;
  for (size_t r = begin; r < end; ++r) s += f(order[r]);
  return s / double(end - begin);
}

double brute_density(const TreeModel& m, size_t i, float r) {
  double f = 0.0;
  glm::vec3 c = leaf_center(m.leaves[i]);
  for (const LeafPlacement& l : m.leaves) {
    glm::vec3 d = leaf_center(l) - c;
    double x = 1.0 - glm::dot(d, d) / (double(r) * r);
    if (x > 0.0) f += x * x;
  }
  return f;
}

// The paper's orders, unstratified (priority_stratify.h).
const PriorityParams kPaper{.stratify_cell = 0.0f};

}  // namespace

TEST(Priority, NamesRoundTrip) {
  for (Priority p : {Priority::random, Priority::density, Priority::orientation, Priority::combined, Priority::layered})
    EXPECT_EQ(parse_priority(priority_name(p)), p);
  EXPECT_EQ(priority_name(Priority::combined), "combined");
  EXPECT_FALSE(parse_priority("Random").has_value());
  EXPECT_FALSE(parse_priority("").has_value());
}

TEST(Priority, EveryOrderIsAPermutationAndDeterministic) {
  Crown c = sphere_crown(3000, 3);
  Hull hull = build_hull(c.model.leaves, 4.0f);
  for (Priority p : {Priority::random, Priority::density, Priority::orientation, Priority::combined, Priority::layered}) {
    std::vector<uint32_t> a = priority_order(c.model, hull, p, 7);
    EXPECT_TRUE(is_permutation(a, c.model.leaves.size())) << priority_name(p);
    EXPECT_EQ(a, priority_order(c.model, hull, p, 7)) << priority_name(p);
    // Seeded where the order is random; orientation and layered (greedy density tail, the
    // rest by orientation) are pure functions of the geometry.
    if (p != Priority::orientation && p != Priority::layered) {
      EXPECT_NE(a, priority_order(c.model, hull, p, 8)) << priority_name(p);
    }
  }
}

TEST(Priority, RandomIsUncorrelatedWithHeight) {
  Crown c = sphere_crown(6000, 4);  // indices sorted by height: the identity would fail
  std::vector<double> height;
  for (const LeafPlacement& l : c.model.leaves) height.push_back(l.position.y);
  std::vector<uint32_t> identity(height.size());
  std::iota(identity.begin(), identity.end(), 0u);
  ASSERT_GT(rank_correlation(identity, height), 0.99);
  for (uint64_t seed : {1u, 2u, 3u}) {
    std::vector<uint32_t> order = priority_order(c.model, Hull{}, Priority::random, seed);
    // Standard error of ρ is 1/sqrt(n) ≈ 0.013.
    EXPECT_LT(std::abs(rank_correlation(order, height)), 0.05) << seed;
  }
}

TEST(Priority, OrientationPutsOutwardFacingLeavesFirst) {
  Crown c = sphere_crown(4000, 5);
  Hull hull = build_hull(c.model.leaves, 4.0f);
  std::vector<uint32_t> order = priority_order(c.model, hull, Priority::orientation, 1, kPaper);
  const size_t n = order.size(), fifth = n / 5;
  double radial_first = mean_over(order, 0, fifth, [&](uint32_t i) { return c.radial[i] ? 1.0 : 0.0; });
  double radial_last = mean_over(order, n - fifth, n, [&](uint32_t i) { return c.radial[i] ? 1.0 : 0.0; });
  EXPECT_GT(radial_first, 0.9);
  EXPECT_LT(radial_last, 0.1);
  // α itself (from the scores): the first fifth is far more aligned with the hull.
  LeafPriorityScores s = leaf_priority_scores(c.model, hull, 1);
  double alpha_first = mean_over(order, 0, fifth, [&](uint32_t i) { return s.alpha[i]; });
  double alpha_last = mean_over(order, n - fifth, n, [&](uint32_t i) { return s.alpha[i]; });
  EXPECT_LT(alpha_first, alpha_last);
  EXPECT_LT(alpha_first, 0.35);  // radians: about 20°
  // α is in [0, 90°] for two-sided cards; P_silhouette = 1 - α / 90°.
  for (size_t i = 0; i < n; ++i) {
    EXPECT_GE(s.alpha[i], 0.0f);
    EXPECT_LE(s.alpha[i], 1.5708f);
    EXPECT_NEAR(s.p_silhouette[i], 1.0f - s.alpha[i] / 1.5707963f, 1e-5f);
  }
}

TEST(Priority, DensityPutsLowDensityLeavesFirst) {
  // A sparse crown with a dense clump inside.
  Crown c = clumped_crown();
  Hull hull = build_hull(c.model.leaves, 4.0f);
  std::vector<uint32_t> order = priority_order(c.model, hull, Priority::density, 3, kPaper);
  const size_t n = order.size(), fifth = n / 5;
  auto dens = [&](uint32_t i) { return brute_density(c.model, i, hull.radius); };
  EXPECT_LT(mean_over(order, 0, fifth, dens), 0.5 * mean_over(order, n - fifth, n, dens));
  // The clump goes first: the last fifth is (almost) all clump leaves.
  EXPECT_GT(mean_over(order, n - fifth, n, [&](uint32_t i) { return i >= 3000 ? 1.0 : 0.0; }), 0.95);
  // The scores expose the initial density, which matches the formula.
  LeafPriorityScores s = leaf_priority_scores(c.model, hull, 3);
  for (size_t i = 0; i < n; i += 97) EXPECT_NEAR(s.density[i], dens(uint32_t(i)), 1e-3 * dens(uint32_t(i)));
}

TEST(Priority, DensitySwitchesToRandomOnceUniform) {
  // After the dense clump is thinned, the survivors come in random order: within the first
  // 20 % (the random phase by default) rank and height are uncorrelated.
  Crown c = sphere_crown(4000, 8);
  Hull hull = build_hull(c.model.leaves, 4.0f);
  std::vector<uint32_t> order = priority_order(c.model, hull, Priority::density, 5, kPaper);
  std::vector<uint32_t> prefix(order.begin(), order.begin() + order.size() / 5);
  std::vector<double> h(c.model.leaves.size());
  for (size_t i = 0; i < h.size(); ++i) h[i] = c.model.leaves[i].position.y;
  // Rank correlation over the prefix only: re-index it compactly.
  std::vector<double> hp;
  std::vector<uint32_t> compact(prefix.size());
  for (size_t r = 0; r < prefix.size(); ++r) hp.push_back(h[prefix[r]]), compact[r] = uint32_t(r);
  EXPECT_LT(std::abs(rank_correlation(compact, hp)), 0.1);
}

TEST(Priority, CombinedIsNormalizedAndFollowsItsScore) {
  Crown c = sphere_crown(3000, 9);
  Hull hull = build_hull(c.model.leaves, 4.0f);
  LeafPriorityScores s = leaf_priority_scores(c.model, hull, 11);
  ASSERT_EQ(s.p_combined.size(), c.model.leaves.size());
  float lo = *std::min_element(s.p_combined.begin(), s.p_combined.end());
  float hi = *std::max_element(s.p_combined.begin(), s.p_combined.end());
  EXPECT_FLOAT_EQ(lo, 0.0f);
  EXPECT_FLOAT_EQ(hi, 1.0f);
  for (size_t i = 0; i < s.p_combined.size(); i += 13) {
    float raw = s.p_silhouette[i] * s.p_silhouette[i] + s.p_density[i];
    float raw_lo = 1e9f, raw_hi = -1e9f;
    for (size_t j = 0; j < s.p_combined.size(); ++j) {
      float r = s.p_silhouette[j] * s.p_silhouette[j] + s.p_density[j];
      raw_lo = std::min(raw_lo, r), raw_hi = std::max(raw_hi, r);
    }
    EXPECT_NEAR(s.p_combined[i], (raw - raw_lo) / (raw_hi - raw_lo), 1e-5f);
  }
  std::vector<uint32_t> order = priority_order(c.model, hull, Priority::combined, 11, kPaper);
  std::vector<double> p(s.p_combined.begin(), s.p_combined.end());
  // Descending in P (small jitter): strongly anti-correlated rank vs P.
  EXPECT_LT(rank_correlation(order, p), -0.95);
  EXPECT_EQ(order, priority_order(c.model, hull, Priority::combined, 11, kPaper));
}

TEST(Priority, ReorderAndApply) {
  Crown c = sphere_crown(500, 10);
  Hull hull = build_hull(c.model.leaves, 4.0f);
  TreeModel m = c.model;
  std::vector<uint32_t> order = priority_order(m, hull, Priority::orientation, 2);
  reorder_leaves(m, order);
  for (size_t r = 0; r < order.size(); ++r) EXPECT_EQ(m.leaves[r].position, c.model.leaves[order[r]].position);
  std::vector<uint32_t> bad = order;
  bad[1] = bad[0];
  EXPECT_THROW(reorder_leaves(m, bad), std::invalid_argument);
  bad.pop_back();
  EXPECT_THROW(reorder_leaves(m, bad), std::invalid_argument);

  TreeModel applied = c.model;
  apply_priority(applied, hull, Priority::orientation, 2);
  EXPECT_EQ(applied.bake.priority, "orientation");
  for (size_t r = 0; r < order.size(); ++r) EXPECT_EQ(applied.leaves[r].position, m.leaves[r].position);
}

TEST(Priority, HullNeededExceptForRandomAndEmptyModels) {
  Crown c = sphere_crown(100, 12);
  EXPECT_THROW(priority_order(c.model, Hull{}, Priority::density, 1), InputError);
  EXPECT_THROW(priority_order(c.model, Hull{}, Priority::combined, 1), InputError);
  EXPECT_EQ(priority_order(c.model, Hull{}, Priority::random, 1).size(), 100u);
  TreeModel empty;
  EXPECT_TRUE(priority_order(empty, Hull{}, Priority::combined, 1).empty());
}

TEST(Priority, LayeredRemovesLikeDensityThenKeepsByOrientation) {
  Crown c = sphere_crown(1500, 5);
  // Denser core: the greedy density phase has something to remove.
  for (size_t i = 0; i < 300; ++i) {
    LeafPlacement l = c.model.leaves[i];
    l.position = glm::vec3(0, 3, 0) + 0.25f * (l.position - glm::vec3(0, 3, 0));
    c.model.leaves.push_back(l);
    c.radial.push_back(c.radial[i]);
  }
  Hull hull = build_hull(c.model.leaves, 4.0f);
  const size_t n = c.model.leaves.size();
  std::vector<uint32_t> layered = priority_order(c.model, hull, Priority::layered, 7, kPaper);
  std::vector<uint32_t> density = priority_order(c.model, hull, Priority::density, 7, kPaper);
  LeafPriorityScores s = leaf_priority_scores(c.model, hull, 7);
  // The tail is density's greedy tail, leaf for leaf; find where the two orders part.
  size_t tail = 0;
  while (tail < n && layered[n - 1 - tail] == density[n - 1 - tail]) ++tail;
  ASSERT_GT(tail, n / 20) << "the dense core should be removed first";
  ASSERT_LT(tail, n - n / 10);
  // The head: ascending α (outward-facing cards survive longest).
  for (size_t k = 1; k < n - tail; ++k) ASSERT_LE(s.alpha[layered[k - 1]], s.alpha[layered[k]]) << k;
  std::vector<uint32_t> head(layered.begin(), layered.end() - std::ptrdiff_t(tail));
  std::vector<uint32_t> survivors(density.begin(), density.end() - std::ptrdiff_t(tail));
  std::sort(head.begin(), head.end());
  std::sort(survivors.begin(), survivors.end());
  EXPECT_EQ(head, survivors);
}

TEST(Priority, StratifiedOrdersKeepEveryRegionInProportion) {
  // A crown with a dense clump: the paper's density order empties the clump first, so a
  // short prefix under-represents it; stratified, every cell keeps about λn of its n leaves.
  Crown c = clumped_crown();
  Hull hull = build_hull(c.model.leaves, 4.0f);
  const size_t n = c.model.leaves.size();
  const float cell = 0.5f * hull.radius;
  std::vector<glm::vec3> centers(n);
  for (size_t i = 0; i < n; ++i) centers[i] = leaf_center(c.model.leaves[i]);
  auto cell_id = [&](uint32_t i) {
    glm::vec3 q = glm::floor(centers[i] / cell);
    return std::make_tuple(int(q.x), int(q.y), int(q.z));
  };
  std::map<std::tuple<int, int, int>, int> total;
  for (uint32_t i = 0; i < n; ++i) ++total[cell_id(i)];
  // Largest deviation of a prefix's per-cell count from λ·n, in leaves.
  auto worst_deviation = [&](const std::vector<uint32_t>& order, double lambda) {
    std::map<std::tuple<int, int, int>, int> kept;
    const size_t k = size_t(std::ceil(lambda * double(n)));
    for (size_t r = 0; r < k; ++r) ++kept[cell_id(order[r])];
    double worst = 0.0;
    for (auto& [id, t] : total) worst = std::max(worst, std::abs(double(kept[id]) - double(k) / double(n) * t));
    return worst;
  };
  for (Priority p : {Priority::density, Priority::orientation, Priority::combined, Priority::layered}) {
    SCOPED_TRACE(std::string(priority_name(p)));
    std::vector<uint32_t> paper = priority_order(c.model, hull, p, 3, kPaper);
    std::vector<uint32_t> order = priority_order(c.model, hull, p, 3);
    EXPECT_TRUE(is_permutation(order, n));
    EXPECT_EQ(order, stratify_order(paper, centers, cell, 3));
    for (double lambda : {0.1, 0.25, 0.5, 0.8}) {
      SCOPED_TRACE(lambda);
      EXPECT_LE(worst_deviation(order, lambda), 1.5);
    }
    if (p == Priority::density) EXPECT_GT(worst_deviation(paper, 0.25), 5.0) << "the clump should be thinned first";
    // Within a cell the order's own choice stands: the leaves of a cell come in the paper order.
    std::vector<size_t> rank(n);
    for (size_t r = 0; r < n; ++r) rank[paper[r]] = r;
    std::map<std::tuple<int, int, int>, size_t> last;
    for (uint32_t i : order) {
      auto [it, added] = last.try_emplace(cell_id(i), rank[i]);
      if (!added) EXPECT_GT(rank[i], it->second), it->second = rank[i];
    }
  }
  EXPECT_EQ(priority_order(c.model, hull, Priority::random, 3), priority_order(c.model, hull, Priority::random, 3, kPaper))
      << "random is Cook's order and stays unstratified";
}
