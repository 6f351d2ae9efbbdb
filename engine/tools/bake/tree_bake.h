// Bake a generated model for run-time pruning: metaball hull, crown depths (self-shadowing),
// priority-sorted leaves and
// PR-measured s_opt / λ_opt tables (stored in model.bake), and the impostor with its Q per size
// (model.impostor, impostor_bake.h). Used by `forest bake` and the species cache.
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "engine/tools/bake/pr_bake.h"

namespace forest {

struct TreeBakeSettings {
  std::string priority = "combined";  // random, density, orientation, combined, layered
  std::optional<uint64_t> seed;       // default: the model's seed
  uint32_t views = 6;
  uint32_t resolution = 512;  // PrBakeOptions::size0
  bool impostor = true;       // bake the impostor atlases and their Q
  std::function<void(double)> progress;  // fraction of the PR measurement done
};

struct TreeBakeResult {
  PrMeasurement measurement;
  double hull_seconds = 0, pr_seconds = 0;  // hull_seconds includes crown_seconds and the priority order
  double crown_seconds = 0;                 // attach_crown_light: per-leaf crown depths and κ
  double impostor_seconds = 0;              // attach_impostor: atlases and their Q per size
  size_t hull_triangles = 0;
};

// InputError for an unknown priority; VkFailure when the validation layer reports anything.
TreeBakeResult bake_tree_model(vk::Context& ctx, TreeModel& model, const TreeBakeSettings& settings);

}  // namespace forest
