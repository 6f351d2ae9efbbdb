// The shared foliage stage: every method's skeleton gets its leaves here, from one set of
// species keys, so that all nine methods carry the same foliage model. Foliage grows on the
// young wood (the outer `foliage_depth` meters of every branch, measured from its farthest
// tip), one element every `shoot_spacing` meters around the branch in a golden-angle spiral,
// tilted outward by `shoot_angle`, plus `shoots_per_tip` elements around every tip. Each of
// them starts a spray: `shoots_per_spray` shoots in a row, each from the end of the one
// before, bending toward the horizontal (a lateral twig system too fine to mesh; the cards
// draw its twigs), as the outer crown of a broadleaf or a spruce branch is built; blades
// face away from the crown's inside (Neubert 2012 ch5 "Twigs and leaves": n_opt from a point
// inside the plant to the bud). An element is a whole shoot (a twig-cluster card carrying
// `leaves_per_shoot` leaves or needle shoots, foliage_card.h) or a single leaf.
// Randomness: a stream of the tree's seed, so this is still the skeleton pass; the card is
// meshed by the model stage from the same keys.
#pragma once
#include <cstdint>
#include <string_view>

#include <glm/glm.hpp>

#include "generators/mesh/foliage_card.h"
#include "generators/tree/tree_graph.h"

namespace forest {

class TomlTable;

enum class Season { summer, autumn };

struct FoliageKeys {
  bool enabled = true;            // false when leaf_size = 0 (a leafless tree)
  ShootDesign shoot;              // foliage, leaf_phyllotaxis, leaves_per_shoot, leaf_size
  float leaf_size = 0.08f;        // blade (or needle shoot) length, meters
  float shoot_length = 0.30f;     // element length, meters (single leaf: leaf_size)
  float size_jitter = 0.2f;       // leaf_size_jitter: element size × (1 ± jitter)
  float spacing = 0.15f;          // shoot_spacing: meters of young wood per element
  float depth = 2.0f;             // foliage_depth: meters of wood below the tips that bear foliage
  float angle_deg = 50.0f;        // shoot_angle: element axis from its branch
  float angle_jitter_deg = 15.0f;
  int per_tip = 3;                // shoots_per_tip
  int per_spray = 1;              // shoots_per_spray: shoots in a row along one lateral spray
  float color_jitter = 0.1f;      // leaf_color_jitter: per-element brightness and yellowing
  Season season = Season::summer;
  glm::vec3 autumn_color{0.55f, 0.30f, 0.06f};  // leaf colour in autumn, linear RGB
  bool evergreen = false;         // autumn keeps the summer colour
};

// Meters above the root below which no foliage element reaches (ground contact).
inline constexpr float kFoliageGroundClearance = 0.3f;

// The keys read_foliage_keys reads; the registry accepts them for every method.
inline constexpr std::string_view kFoliageKeys[] = {
    "foliage",        "leaf_size",   "leaf_size_jitter", "leaf_phyllotaxis", "leaves_per_shoot",
    "shoot_length",   "shoot_spacing", "foliage_depth",  "shoot_angle",      "shoot_angle_jitter",
    "shoots_per_tip", "leaf_color_jitter", "leaf_angle", "season",           "autumn_color",
    "evergreen",      "shoots_per_spray"};

// Reads the foliage keys of a species table (leaf_shape comes from the look keys); absent
// keys keep FoliageKeys' defaults. Out of range or wrong type -> InputError (file, line, key).
FoliageKeys read_foliage_keys(const TomlTable& species, LeafShape leaf_shape);

// The leaf material colour for the season: summer_color, or autumn_color in autumn unless
// the species is evergreen.
glm::vec3 season_leaf_color(const FoliageKeys& keys, glm::vec3 summer_color);

// Replaces graph.leaves with the foliage (radii must be set). Deterministic in `seed`.
void place_foliage(TreeGraph& graph, const FoliageKeys& keys, uint64_t seed);

// For foliage a method placed itself: sets each element's size (element length × (1 ±
// jitter)) and colour variation, keeping position and orientation. Deterministic in `seed`.
void size_foliage(TreeGraph& graph, const FoliageKeys& keys, uint64_t seed);

// Path length from each node to the farthest tip of its subtree (0 at tips).
std::vector<float> length_to_farthest_tip(const TreeGraph& graph);

}  // namespace forest
