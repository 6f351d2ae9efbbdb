// The botanical habit a species preset claims for itself, as data: an optional [habit] table
// of the preset (cited in its comments) with the ranges its generated tree must measure
// inside (habit.h). The registry checks the table before the skeleton pass; no method reads
// it (it shapes nothing). `forest measure` prints each metric against its range and a unit
// test holds every preset to its ranges.
//
//   [habit]
//   crown_width_over_height = [0.6, 1.0]   # HabitMetrics::crown_ratio
//   clear_bole_over_height = [0.1, 0.3]    # HabitMetrics::clear_bole
//   trunk_fraction_min = 0.25              # HabitMetrics::trunk_fraction >= this (broadleaves)
//   single_leader = true                   # HabitMetrics::single_leader required (excurrent)
//   lowest_leaf_over_height_min = 0.2      # HabitMetrics::lowest_leaf >= this (the crown
//                                          # does not reach the ground)
#pragma once
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "generators/tree/habit.h"

namespace forest {

class TomlTable;

// The species-file key of the table (for the registry's key check).
inline constexpr std::string_view kHabitKeys[] = {"habit"};

struct HabitRanges {
  std::optional<glm::dvec2> crown_ratio;  // [lo, hi] of crown width ÷ H
  std::optional<glm::dvec2> clear_bole;   // [lo, hi] of clear bole ÷ H
  std::optional<double> trunk_fraction_min;
  bool single_leader = false;             // a single leader is required
  // The lowest leaf at least this fraction of H up. The clear bole is where the first limb
  // leaves the trunk; limbs that droop can still hang their foliage to the ground (the
  // magnetic oak did at 0.03 H with a clear bole of 0.28, peer pictures in the README).
  std::optional<double> lowest_leaf_min;
};

// The species' [habit] table, or nullopt when it has none. Bad table, unknown key, a range
// that is not [lo, hi] with 0 <= lo <= hi (<= 1 for fractions of H), an empty table ->
// InputError naming file, line and key.
std::optional<HabitRanges> read_habit_ranges(const TomlTable& species);

// One metric against its range.
struct HabitCheck {
  std::string key;     // the [habit] key
  double value = 0;    // measured (single_leader: 1 yes, 0 no)
  double lo = 0, hi = 0;  // a *_min key: [min, 1]; single_leader: [1, 1]
  bool ok = false;
  std::string range_text() const;  // "0.60-1.00", ">= 0.25", "required"
};

// The checks of every range `ranges` sets, in the order of the table above.
std::vector<HabitCheck> check_habit(const HabitMetrics& metrics, const HabitRanges& ranges);

}  // namespace forest
