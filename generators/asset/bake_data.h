// What the bake adds to a model besides its hull mesh and leaf order, typed: the hull's
// occlusion samples, the name of the leaf order, the PR tables and the PR diagram behind them.
// TreeModel::bake holds it; in a .glb it travels in extras.forest (keys below), converted and
// validated only here, at the asset boundary (bake_to_json / bake_from_json, called by
// encode_glb / decode_glb).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "generators/core/limits.h"

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "generators/asset/pr_tables.h"

namespace forest {

// Sample points on the metaball hull for the run-time occlusion test (Neubert 2012 §7.4).
struct HullSamples {
  std::vector<glm::vec3> points;   // hull_samples: model space, on the hull mesh
  std::vector<glm::vec3> normals;  // hull_sample_normals: one per point, outward, unit
  float iso = 0.0f;                // hull_iso: iso-value a of the metaball field
  float radius = 0.0f;             // hull_radius: metaball radius r, metres
};

// One measured point of the PR diagram: detail λ, leaf area scale s, precision and recall of
// the pixel counts summed over the views.
struct PrPoint {
  float lambda = 0.0f, scale = 0.0f;
  double precision = 0.0, recall = 0.0;
};

struct BakeData {
  std::optional<HullSamples> hull;    // attach_hull
  std::string priority;               // apply_priority: the leaves' order ("" = generation order)
  std::optional<PrTables> pr_tables;  // bake_tree_model; a model is baked iff set
  std::vector<PrPoint> pr_samples;    // bake_tree_model: stored with pr_tables only
  bool baked() const { return pr_tables.has_value(); }
};

// The extras.forest keys bake data occupies.
inline constexpr const char* kBakeKeys[] = {"baked",      "hull_iso",  "hull_radius", "hull_sample_normals",
                                            "hull_samples", "pr_samples", "pr_tables",   "priority"};

// Hull samples whose points and normals pass these checks on load.
inline constexpr float kUnitNormalTolerance = 1e-3f;  // | |n| − 1 | allowed

// Adds the bake keys to `forest` (an extras.forest object): hull_samples, hull_sample_normals,
// hull_iso, hull_radius when bake.hull is set; priority when not empty; pr_tables, pr_samples
// and baked = true when bake.pr_tables is set. std::logic_error when `forest` already holds one
// of the keys (bake data belongs in TreeModel::bake) or pr_samples come without tables.
void bake_to_json(const BakeData& bake, nlohmann::json& forest);

// Moves the bake keys out of `forest` into typed data. InputError naming `name` and
// extras.forest.<key> for anything malformed: a wrong type or size, non-finite numbers, a
// normal that is not unit length, sample and normal counts that differ, half of the hull
// keys, an unknown priority, tables out of range or off their derivation (pr_tables.cpp), PR
// samples or a `baked` flag without tables (or tables without them), tables measured with
// another order than the leaves'.
BakeData bake_from_json(nlohmann::json& forest, const std::string& name);

}  // namespace forest
