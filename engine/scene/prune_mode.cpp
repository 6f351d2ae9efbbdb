#include "engine/scene/prune_mode.h"

namespace forest {

namespace {
const std::string kNames[] = {"full", "cook", "opt", "target"};
constexpr PruneMode kModes[] = {PruneMode::full, PruneMode::cook, PruneMode::opt, PruneMode::target};
}  // namespace

std::span<const std::string> prune_mode_names() { return kNames; }

std::optional<PruneMode> parse_prune_mode(std::string_view name) {
  for (size_t i = 0; i < std::size(kNames); ++i)
    if (name == kNames[i]) return kModes[i];
  return std::nullopt;
}

const char* prune_mode_name(PruneMode mode) {
  for (size_t i = 0; i < std::size(kModes); ++i)
    if (mode == kModes[i]) return kNames[i].c_str();
  return "fixed";
}

}  // namespace forest
