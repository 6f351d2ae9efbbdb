#include "generators/bake/priority/priority.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <stdexcept>

#include "generators/bake/hull/hull_field.h"
#include "generators/bake/hull/hull_nearest.h"
#include "generators/bake/priority/priority_density.h"
#include "generators/bake/priority/priority_stratify.h"
#include "generators/core/input_error.h"
#include "generators/core/rng.h"

namespace forest {

namespace {

constexpr uint64_t kShuffleStream = 0x5348'5546ull;
constexpr uint64_t kTieStream = 0x5449'4553ull;
constexpr uint64_t kJitterStream = 0x4A49'5454ull;

std::vector<uint32_t> shuffled(size_t n, uint64_t seed) {
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  Rng rng(seed, kShuffleStream);
  for (size_t i = n; i > 1; --i) {
    size_t j = std::min(i - 1, size_t(rng.uniform() * double(i)));
    std::swap(order[i - 1], order[j]);
  }
  return order;
}

// Indices sorted by key descending; equal keys in a seeded random order (never by index,
// which would correlate with the generator's placement order, e.g. height).
std::vector<uint32_t> sort_descending(const std::vector<double>& key, uint64_t seed) {
  std::vector<uint32_t> order(key.size());
  std::iota(order.begin(), order.end(), 0u);
  std::vector<uint64_t> tie(key.size());
  for (size_t i = 0; i < key.size(); ++i) tie[i] = hash64(seed, kTieStream, i);
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    if (key[a] != key[b]) return key[a] > key[b];
    if (tie[a] != tie[b]) return tie[a] < tie[b];
    return a < b;
  });
  return order;
}

void require_hull(const TreeModel& model, const Hull& hull, Priority p) {
  if (model.leaves.empty()) return;
  if (hull.mesh.indices.empty() || !(hull.radius > 0.0f))
    throw InputError("", 0, "priority",
                     std::string(priority_name(p)) + " needs a hull: build it before ordering");
}

}  // namespace

LeafPriorityScores leaf_priority_scores(const TreeModel& model, const Hull& hull, uint64_t seed,
                                        const PriorityParams& params) {
  require_hull(model, hull, Priority::combined);
  LeafPriorityScores s;
  const size_t n = model.leaves.size();
  if (n == 0) return s;

  std::vector<glm::vec3> centers(n);
  for (size_t i = 0; i < n; ++i) centers[i] = leaf_center(model.leaves[i]);
  MetaballField field = make_metaball_field(centers, hull.radius);
  s.density = field_at_centers(field);

  // α at the nearest hull point (Neubert 2012 §7.3.3).
  MeshNearest nearest = make_mesh_nearest(hull.mesh);
  const float alpha_max = params.two_sided ? 0.5f * std::numbers::pi_v<float> : std::numbers::pi_v<float>;
  s.alpha.resize(n);
  s.p_silhouette.resize(n);
  for (size_t i = 0; i < n; ++i) {
    NearestHit hit = nearest_on_mesh(nearest, centers[i]);
    float c = glm::dot(leaf_normal(model.leaves[i]), hit.normal);
    if (params.two_sided) c = std::abs(c);
    s.alpha[i] = std::acos(std::clamp(c, -1.0f, 1.0f));
    s.p_silhouette[i] = 1.0f - s.alpha[i] / alpha_max;
  }

  // P_density from the rank in the density order, so it carries that order's switch to
  // random at small λ.
  std::vector<uint32_t> dorder =
      density_order(field, {params.density_uniform_cv, params.density_random_below}, seed);
  s.p_density.resize(n);
  for (size_t rank = 0; rank < n; ++rank)
    s.p_density[dorder[rank]] = n > 1 ? 1.0f - float(rank) / float(n - 1) : 1.0f;

  // (7.8) P = P_sil² + P_dens, normalized to [0, 1].
  s.p_combined.resize(n);
  float lo = std::numeric_limits<float>::max(), hi = -lo;
  for (size_t i = 0; i < n; ++i) {
    s.p_combined[i] = s.p_silhouette[i] * s.p_silhouette[i] + s.p_density[i];
    lo = std::min(lo, s.p_combined[i]), hi = std::max(hi, s.p_combined[i]);
  }
  for (float& p : s.p_combined) p = hi > lo ? (p - lo) / (hi - lo) : 1.0f;
  return s;
}

std::vector<uint32_t> priority_order(const TreeModel& model, const Hull& hull, Priority p,
                                     uint64_t seed) {
  return priority_order(model, hull, p, seed, PriorityParams{});
}

namespace {

std::vector<uint32_t> paper_order(const TreeModel& model, const Hull& hull, Priority p, uint64_t seed,
                                  const PriorityParams& params) {
  const size_t n = model.leaves.size();
  if (p == Priority::random) return shuffled(n, seed);
  require_hull(model, hull, p);
  if (n == 0) return {};

  if (p == Priority::density) {
    std::vector<glm::vec3> centers(n);
    for (size_t i = 0; i < n; ++i) centers[i] = leaf_center(model.leaves[i]);
    MetaballField field = make_metaball_field(std::move(centers), hull.radius);
    return density_order(field, {params.density_uniform_cv, params.density_random_below}, seed);
  }

  LeafPriorityScores s = leaf_priority_scores(model, hull, seed, params);
  if (p == Priority::layered) {
    std::vector<glm::vec3> centers(n);
    for (size_t i = 0; i < n; ++i) centers[i] = leaf_center(model.leaves[i]);
    MetaballField field = make_metaball_field(std::move(centers), hull.radius);
    size_t removed = 0;
    std::vector<uint32_t> dorder =
        density_order(field, {params.density_uniform_cv, params.density_random_below}, seed, &removed);
    // Survivors by ascending α: a key of −α for them, below every survivor for the rest.
    std::vector<double> key(n, -10.0);
    for (size_t k = 0; k + removed < n; ++k) key[dorder[k]] = -double(s.alpha[dorder[k]]);
    std::vector<uint32_t> order = sort_descending(key, seed);
    std::copy(dorder.end() - std::ptrdiff_t(removed), dorder.end(), order.end() - std::ptrdiff_t(removed));
    return order;
  }
  std::vector<double> key(n);
  if (p == Priority::orientation) {
    for (size_t i = 0; i < n; ++i) key[i] = -double(s.alpha[i]);
  } else {
    Rng rng(seed, kJitterStream);
    for (size_t i = 0; i < n; ++i) key[i] = double(s.p_combined[i]) + params.combined_jitter * rng.symmetric();
  }
  return sort_descending(key, seed);
}

}  // namespace

std::vector<uint32_t> priority_order(const TreeModel& model, const Hull& hull, Priority p,
                                     uint64_t seed, const PriorityParams& params) {
  std::vector<uint32_t> order = paper_order(model, hull, p, seed, params);
  if (p == Priority::random || !(params.stratify_cell > 0.0f) || order.empty()) return order;
  std::vector<glm::vec3> centers(order.size());
  for (size_t i = 0; i < order.size(); ++i) centers[i] = leaf_center(model.leaves[i]);
  return stratify_order(order, centers, params.stratify_cell * hull.radius, seed);
}

void reorder_leaves(TreeModel& model, std::span<const uint32_t> order) {
  const size_t n = model.leaves.size();
  if (order.size() != n) throw std::invalid_argument("reorder_leaves: order has the wrong length");
  std::vector<bool> seen(n, false);
  std::vector<LeafPlacement> out;
  out.reserve(n);
  for (uint32_t i : order) {
    if (i >= n || seen[i]) throw std::invalid_argument("reorder_leaves: order is not a permutation");
    seen[i] = true;
    out.push_back(model.leaves[i]);
  }
  model.leaves = std::move(out);
  // Per-leaf bake data follows its leaf.
  if (model.bake.crown && model.bake.crown->depths.size() == n) {
    std::vector<CrownCube> depths;
    depths.reserve(n);
    for (uint32_t i : order) depths.push_back(model.bake.crown->depths[i]);
    model.bake.crown->depths = std::move(depths);
  }
}

void apply_priority(TreeModel& model, const Hull& hull, Priority p, uint64_t seed) {
  std::vector<uint32_t> order = priority_order(model, hull, p, seed);
  reorder_leaves(model, order);
  model.bake.priority = std::string(priority_name(p));
}

}  // namespace forest
