// How many leaves of each tree a frame draws (Neubert 2012 ch7): the one list of prune
// modes, their names in scene files and on the command line, and their GPU values
// (FrameData.prune_mode, PRUNE_* in shaders/gpu_types.h).
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "gpu_types.h"

namespace forest {

enum class PruneMode : uint32_t {
  full = PRUNE_FULL,    // every leaf, λ = 1
  cook = PRUNE_COOK,    // λ = (1 − d)², s = 1/λ (Cook et al. 2007)
  opt = PRUNE_OPT,      // λ_opt(d), s_opt(λ) from the model's baked PR tables
  fixed = PRUNE_FIXED,  // one λ and s for every tree: bake measurements and tests, never named by a user
  // The smallest λ, with its s_opt, whose baked Q at the tree's projected size reaches a
  // quality the user chooses ([render] quality, --quality): no prune distance involved.
  target = PRUNE_TARGET,
};

// The modes a user names ([render] mode, --mode): "full", "cook", "opt", "target".
std::span<const std::string> prune_mode_names();
// nullopt for anything but one of prune_mode_names().
std::optional<PruneMode> parse_prune_mode(std::string_view name);
// "full", "cook", "opt", "target" or "fixed".
const char* prune_mode_name(PruneMode mode);

}  // namespace forest
