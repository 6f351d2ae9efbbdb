#include "engine/tools/measure/tree_measure.h"

#include <cmath>
#include <cstdio>

namespace forest {

namespace {

std::string format(const char* fmt, auto... values) {
  char buf[256];
  std::snprintf(buf, sizeof buf, fmt, values...);
  return buf;
}

// JSON numbers rounded to what the measurements resolve (stable, diffable files).
double rounded(double v, double digits = 1e4) { return std::round(v * digits) / digits; }

nlohmann::json habit_json(const HabitMetrics& h) {
  return {{"nodes", h.nodes},
          {"height_m", rounded(h.height)},
          {"crown_width_m", rounded(h.crown_width)},
          {"crown_width_x_m", rounded(h.crown_width_x)},
          {"crown_width_z_m", rounded(h.crown_width_z)},
          {"crown_width_over_height", rounded(h.crown_ratio)},
          {"crown_base_m", rounded(h.crown_base)},
          {"clear_bole_over_height", rounded(h.clear_bole)},
          {"lowest_leaf_over_height", rounded(h.lowest_leaf)},
          {"stem_nodes", h.stem_nodes},
          {"trunk_height_m", rounded(h.trunk_height)},
          {"trunk_fraction", rounded(h.trunk_fraction)},
          {"codominant_fork", h.codominant_fork},
          {"single_leader", h.single_leader}};
}

// " (range 0.60-1.00: in range)" for the check of `key`, "" when the species sets none.
std::string range_note(const std::vector<HabitCheck>& checks, const std::string& key) {
  for (const HabitCheck& c : checks)
    if (c.key == key) return " [range " + c.range_text() + ": " + (c.ok ? "in range" : "OUT OF RANGE") + "]";
  return "";
}

nlohmann::json ranges_json(const std::vector<HabitCheck>& checks) {
  nlohmann::json out = nlohmann::json::object();
  for (const HabitCheck& c : checks) {
    nlohmann::json r = {{"value", rounded(c.value)}, {"in_range", c.ok}};
    if (c.key == "single_leader")
      r["required"] = true;
    else if (c.key == "trunk_fraction_min")
      r["min"] = rounded(c.lo);
    else
      r["range"] = {rounded(c.lo), rounded(c.hi)};
    out[c.key] = r;
  }
  return out;
}

}  // namespace

TreeMeasurement measure_tree(vk::Context& ctx, const TreeModel& model, const TreeGraph* graph,
                             const LeafCoverageOptions& coverage) {
  TreeMeasurement m;
  m.name = model.meta.value("species", "");
  m.leaves = uint32_t(model.leaves.size());
  if (graph) m.habit = measure_habit(*graph);
  m.coverage = measure_leaf_coverage(ctx, model, coverage);
  m.depth = measure_crown_depth(model.leaves);
  return m;
}

std::vector<std::string> measurement_lines(const TreeMeasurement& m) {
  std::vector<std::string> out;
  out.push_back(format("leaves %u", m.leaves));
  if (const HabitMetrics* h = m.habit ? &*m.habit : nullptr) {
    const std::vector<HabitCheck> checks = m.ranges ? check_habit(*h, *m.ranges) : std::vector<HabitCheck>{};
    out.push_back(format("height_m %.2f", h->height));
    out.push_back(format("crown_width_m %.2f (x %.2f, z %.2f)", h->crown_width, h->crown_width_x, h->crown_width_z));
    out.push_back(format("crown_width_over_height %.3f", h->crown_ratio) + range_note(checks, "crown_width_over_height"));
    out.push_back(format("clear_bole_over_height %.3f (crown base %.2f m)", h->clear_bole, h->crown_base) +
                  range_note(checks, "clear_bole_over_height"));
    out.push_back(format("trunk_fraction %.3f (trunk %.2f m, %s)", h->trunk_fraction, h->trunk_height,
                         h->codominant_fork ? "then a codominant fork" : "no codominant fork") +
                  range_note(checks, "trunk_fraction_min"));
    out.push_back(format("single_leader %s", h->single_leader ? "yes" : "no") + range_note(checks, "single_leader"));
    out.push_back(format("lowest_leaf_over_height %.3f", h->lowest_leaf) + range_note(checks, "lowest_leaf_over_height_min"));
    if (!checks.empty()) {
      size_t ok = 0;
      for (const HabitCheck& c : checks) ok += c.ok;
      out.push_back(format("habit_in_range %zu / %zu", ok, checks.size()));
    }
  } else {
    out.push_back("habit n/a (needs the skeleton: measure a --species)");
  }
  for (const ViewCoverage& v : m.coverage.views)
    out.push_back(format("coverage_az%03.0f %.3f (%llu leaf pixels / %.0f in their hull)", v.azimuth_deg, v.mask.coverage(),
                         (unsigned long long)v.mask.pixels, v.mask.hull_area));
  out.push_back(format("coverage_min %.3f", m.coverage.min));
  const CrownDepth& d = m.depth;
  out.push_back(format("depth_m q1 %.3f median %.3f q3 %.3f", d.q1, d.median, d.q3));
  out.push_back(format("depth_over_half_width q1 %.3f median %.3f q3 %.3f (half width %.2f m)", d.q1_rel, d.median_rel,
                       d.q3_rel, d.half_width));
  std::string hist = "depth_histogram";
  for (float f : d.histogram) hist += format(" %.3f", f);
  out.push_back(hist + " (fractions per 0.1 of depth / half width)");
  return out;
}

nlohmann::json measurement_json(const TreeMeasurement& m) {
  nlohmann::json views = nlohmann::json::array();
  for (const ViewCoverage& v : m.coverage.views)
    views.push_back({{"azimuth_deg", v.azimuth_deg},
                     {"coverage", rounded(v.mask.coverage())},
                     {"leaf_pixels", v.mask.pixels},
                     {"hull_pixels", v.mask.hull_area}});
  const CrownDepth& d = m.depth;
  nlohmann::json hist = nlohmann::json::array();
  for (float f : d.histogram) hist.push_back(rounded(f));
  return {{"species", m.name},
          {"leaves", m.leaves},
          {"habit", m.habit ? habit_json(*m.habit) : nlohmann::json(nullptr)},
          {"habit_ranges", m.habit && m.ranges ? ranges_json(check_habit(*m.habit, *m.ranges)) : nlohmann::json(nullptr)},
          {"coverage", {{"resolution", m.coverage.resolution}, {"views", views}, {"min", rounded(m.coverage.min)}}},
          {"depth",
           {{"solid", d.solid},
            {"half_width_m", rounded(d.half_width)},
            {"q1_m", rounded(d.q1)},
            {"median_m", rounded(d.median)},
            {"q3_m", rounded(d.q3)},
            {"q1_rel", rounded(d.q1_rel)},
            {"median_rel", rounded(d.median_rel)},
            {"q3_rel", rounded(d.q3_rel)},
            {"histogram", hist}}}};
}

}  // namespace forest
