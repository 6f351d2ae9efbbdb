// What the bake adds to a model besides its hull mesh and leaf order, typed: the hull's
// occlusion samples, the name of the leaf order, the PR tables and the PR diagram behind them.
// TreeModel::bake holds it; in a .glb it travels in extras.forest (keys below), converted and
// validated only here, at the asset boundary (bake_to_json / bake_from_json, called by
// encode_glb / decode_glb).
#pragma once
#include <array>
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

// One measured point of the PR diagram: detail λ, leaf area scale s, projected size (pixels
// across the bounding sphere), precision and recall of the pixel counts summed over the views.
struct PrPoint {
  float lambda = 0.0f, scale = 0.0f, size = 0.0f;
  double precision = 0.0, recall = 0.0;
};

// Crown self-shadowing (attach_crown_light, generators/bake/hull/hull_depth.h): per leaf the
// depth below the hull along +x, −x, +y, −y, +z, −z (metres, model space), the ambient-cube
// coefficients of D(ω) = Σ_i ω_i² · D[axis i, sign of ω_i]; and the foliage's extinction κ.
using CrownCube = std::array<float, 6>;
struct CrownLight {
  std::vector<CrownCube> depths;  // index-aligned with TreeModel::leaves (reorder_leaves keeps it so)
  float extinction = 0.0f;         // κ, 1/m: transmittance exp(−κ · depth)
};

struct BakeData {
  std::optional<HullSamples> hull;    // attach_hull
  std::optional<CrownLight> crown;    // attach_crown_light: crown_extinction; the depths travel as leaf attributes
  std::string priority;               // apply_priority: the leaves' order ("" = generation order)
  std::optional<PrTables> pr_tables;  // bake_tree_model; a model is baked iff set
  std::vector<PrPoint> pr_samples;    // bake_tree_model: stored with pr_tables only
  bool baked() const { return pr_tables.has_value(); }
};

// The extras.forest keys bake data occupies.
inline constexpr const char* kBakeKeys[] = {"baked",        "crown_extinction", "hull_iso",  "hull_radius",
                                            "hull_sample_normals", "hull_samples", "pr_samples", "pr_tables",
                                            "priority"};

// Hull samples whose points and normals pass these checks on load.
inline constexpr float kUnitNormalTolerance = 1e-3f;  // | |n| − 1 | allowed
// crown_extinction on load: a number in (0, this] (1/m; the bake writes at most 3).
inline constexpr double kMaxCrownExtinctionOnLoad = 100.0;
// Crown depths (the leaves' _CROWN_DEPTH_POS / _NEG attributes) on load: finite, in [0, this] m.
inline constexpr float kMaxCrownDepthOnLoad = 1e6f;

// Adds the bake keys to `forest` (an extras.forest object): hull_samples, hull_sample_normals,
// hull_iso, hull_radius when bake.hull is set; crown_extinction when bake.crown is (its depths
// are written by encode_glb as leaf attributes); priority when not empty; pr_tables, pr_samples
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
