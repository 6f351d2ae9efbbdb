// Synthesis from a planton model (Wang 2006 §6): a planton tree grown from the root planton —
// child count ~ 𝓝 (rounded, ≥ 0), child planton ~ p_i·, position t ~ T, direction ~ Ω —
// then one organ per planton: the exemplar of the planton nearest to a sample of 𝓖, scaled
// to the sampled size. Breadth-first, so the caps cut the tree evenly.
#pragma once
#include <cstdint>
#include <vector>

#include "generators/methods/plantons/plantons_model.h"

namespace forest {

struct SynthesisParams {
  size_t max_organs = 20000;  // [ours] size cap
  uint32_t max_depth = 12;    // [ours] depth cap (the root stem has depth 0)
};

struct SynthesizedTree {
  OrganTree tree;
  std::vector<uint32_t> plantons;  // planton of each organ
  bool capped = false;             // a cap stopped growth
};

// Deterministic for (model, params, seed). The model must be subcritical (checked by
// load_model / learn_plantons); this function only obeys the caps.
SynthesizedTree synthesize_plantons(const PlantonModel& model, const SynthesisParams& params, uint64_t seed);

}  // namespace forest
