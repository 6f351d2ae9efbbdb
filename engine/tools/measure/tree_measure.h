// Everything `forest measure` reports about one tree: habit of its skeleton
// (generators/tree/habit.h), leaf coverage of side views (leaf_coverage.h) and leaf depth
// below the crown's hull (generators/tree/crown_depth.h), as text lines and as JSON.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/tools/measure/leaf_coverage.h"
#include "generators/tree/crown_depth.h"
#include "generators/tree/habit.h"
#include "generators/tree/habit_ranges.h"

namespace forest {

struct TreeMeasurement {
  std::string name;  // the model's species name (extras.forest.species), else empty
  uint32_t leaves = 0;
  std::optional<HabitMetrics> habit;  // only with the skeleton (a .glb has none)
  // The species' [habit] ranges (habit_ranges.h), when it has them: the text lines and the
  // JSON put each habit metric next to its range and say whether it is inside.
  std::optional<HabitRanges> ranges;
  LeafCoverage coverage;
  CrownDepth depth;  // of model.leaves, the leaves the coverage views draw
};

// `graph`: the skeleton `model` was meshed from (GenerateOptions::skeleton), or nullptr.
TreeMeasurement measure_tree(vk::Context& ctx, const TreeModel& model, const TreeGraph* graph,
                             const LeafCoverageOptions& coverage = {});

// One line per metric, "key value", for the terminal.
std::vector<std::string> measurement_lines(const TreeMeasurement& m);

// The same numbers as JSON (habit null without a skeleton).
nlohmann::json measurement_json(const TreeMeasurement& m);

}  // namespace forest
