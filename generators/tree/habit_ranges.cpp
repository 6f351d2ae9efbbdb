#include "generators/tree/habit_ranges.h"

#include <cstdio>

#include "generators/core/toml_reader.h"

namespace forest {

std::optional<HabitRanges> read_habit_ranges(const TomlTable& species) {
  std::optional<TomlTable> t = species.table("habit");
  if (!t) return std::nullopt;
  t->check_keys({"crown_width_over_height", "clear_bole_over_height", "trunk_fraction_min", "single_leader",
                 "lowest_leaf_over_height_min"});
  if (t->raw().empty()) species.fail("habit", "an empty [habit] table: give at least one range or drop it");
  HabitRanges r;
  // A crown may be several times wider than tall (a shrub), never negative; the other two
  // are fractions of the height.
  if (t->has("crown_width_over_height")) r.crown_ratio = t->interval("crown_width_over_height", 0.0, 10.0);
  if (t->has("clear_bole_over_height")) r.clear_bole = t->interval("clear_bole_over_height", 0.0, 1.0);
  if (t->has("trunk_fraction_min")) r.trunk_fraction_min = t->number("trunk_fraction_min", 0.0, 1.0);
  r.single_leader = t->boolean("single_leader", false);
  if (t->has("lowest_leaf_over_height_min"))
    r.lowest_leaf_min = t->number("lowest_leaf_over_height_min", 0.0, 1.0);
  return r;
}

std::string HabitCheck::range_text() const {
  char buf[64];
  if (key == "single_leader")
    return "required";
  else if (key.ends_with("_min"))
    std::snprintf(buf, sizeof buf, ">= %.2f", lo);
  else
    std::snprintf(buf, sizeof buf, "%.2f-%.2f", lo, hi);
  return buf;
}

std::vector<HabitCheck> check_habit(const HabitMetrics& m, const HabitRanges& r) {
  std::vector<HabitCheck> out;
  auto within = [&](const char* key, double v, double lo, double hi) {
    out.push_back(HabitCheck{key, v, lo, hi, v >= lo && v <= hi});
  };
  if (r.crown_ratio) within("crown_width_over_height", m.crown_ratio, r.crown_ratio->x, r.crown_ratio->y);
  if (r.clear_bole) within("clear_bole_over_height", m.clear_bole, r.clear_bole->x, r.clear_bole->y);
  if (r.trunk_fraction_min) within("trunk_fraction_min", m.trunk_fraction, *r.trunk_fraction_min, 1.0);
  if (r.single_leader) within("single_leader", m.single_leader ? 1.0 : 0.0, 1.0, 1.0);
  if (r.lowest_leaf_min) within("lowest_leaf_over_height_min", m.lowest_leaf, *r.lowest_leaf_min, 1.0);
  return out;
}

}  // namespace forest
