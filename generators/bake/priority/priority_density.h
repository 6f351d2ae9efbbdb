// Density-normalizing survival order (Neubert 2012 §7.3.2): leaves in dense regions of the
// metaball field go first, because their pixels are likely covered by neighbours anyway.
// Our reading of "switch back to stochastic prioritization at small λ": remove the leaf of
// highest *current* density, subtract its contribution from its neighbours, and repeat while
// the density still varies (coefficient of variation over the remaining leaves above a
// threshold) and enough leaves remain; the leaves left then survive in random order.
#pragma once
#include <cstdint>
#include <vector>

#include "generators/bake/hull/hull_field.h"

namespace forest {

struct DensityOrderParams {
  float uniform_cv = 0.15f;     // stop the greedy phase once std(F) / mean(F) <= this
  float random_below = 0.2f;    // ... or once only this fraction of leaves remains
};

// Leaf indices (generators of `field`) in descending survival. Deterministic in seed.
// `greedy_removed`, when given, receives how many leaves the greedy phase removed: they are
// the last ones of the order, the others (the random survivors) come first.
std::vector<uint32_t> density_order(const MetaballField& field, const DensityOrderParams& params,
                                    uint64_t seed, size_t* greedy_removed = nullptr);

}  // namespace forest
