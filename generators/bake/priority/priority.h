// Rendering priority of leaves (Neubert 2012 §7.3):
// the order in which leaves survive pruning. The baked asset stores its leaves in this order,
// so rendering a detail level λ is drawing a prefix of ⌈λ·N⌉ leaves.
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "generators/bake/hull/hull.h"
#include "generators/bake/priority/priority_names.h"
#include "generators/model/tree_model.h"

namespace forest {

struct PriorityParams {
  // Density order: greedy removal of the currently densest leaf (F updated as leaves go)
  // while the coefficient of variation of F over the remaining leaves exceeds this...
  float density_uniform_cv = 0.15f;
  // ...and more than this fraction of leaves remains; the rest survive in random order.
  float density_random_below = 0.2f;
  // Leaf cards are two-sided: α = angle between the card's plane normal and the hull normal,
  // folded into [0, 90°] (a card whose back faces out covers the same pixels).
  bool two_sided = true;
  float combined_jitter = 0.02f;  // uniform ± jitter added to the normalized P_combined
  // Every order but random (Cook's) is stratified in cubic cells of this edge, as a fraction
  // of the hull's metaball radius (priority_stratify.h says why); 0 gives the paper's orders.
  float stratify_cell = 0.5f;
};

// Per-leaf quantities behind the orders (index-aligned with model.leaves).
struct LeafPriorityScores {
  std::vector<float> density;        // F at the leaf centre (initial, all leaves present)
  std::vector<float> alpha;          // radians, see PriorityParams::two_sided
  std::vector<float> p_silhouette;   // 1 - α / α_max, in [0, 1]
  std::vector<float> p_density;      // 1 - rank / (N - 1) in the density order, in [0, 1]
  std::vector<float> p_combined;     // (P_sil² + P_dens) normalized to [0, 1], no jitter
};

LeafPriorityScores leaf_priority_scores(const TreeModel& model, const Hull& hull,
                                        uint64_t seed, const PriorityParams& params = {});

// Leaf indices in descending survival (a permutation of 0..N-1). Deterministic in seed.
// Throws InputError if the hull is needed (all but random) and has no mesh while leaves exist.
std::vector<uint32_t> priority_order(const TreeModel& model, const Hull& hull, Priority p,
                                     uint64_t seed);
std::vector<uint32_t> priority_order(const TreeModel& model, const Hull& hull, Priority p,
                                     uint64_t seed, const PriorityParams& params);

// model.leaves = old leaves[order[0]], leaves[order[1]], ...; throws std::invalid_argument
// unless order is a permutation of the leaf indices.
void reorder_leaves(TreeModel& model, std::span<const uint32_t> order);

// priority_order + reorder_leaves + model.bake.priority = priority_name(p).
void apply_priority(TreeModel& model, const Hull& hull, Priority p, uint64_t seed);

}  // namespace forest
