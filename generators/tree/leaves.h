// The geometry of one leaf (Neubert 2012 ch5 "Twigs and leaves"): phyllotaxis, the leaf frame
// rule and per-leaf colour. The foliage stage (foliage.h) places elements with these; the
// foliage card (mesh/foliage_card.h) arranges the leaves of a shoot with them.
#pragma once
#include <cstdint>
#include <optional>
#include <string_view>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "generators/core/rng.h"
#include "generators/tree/tree_graph.h"

namespace forest {

// Phyllotaxis: how the leaves of successive nodes of a twig turn around it.
enum class Phyllotaxis {
  alternate,  // distichous: one leaf per node, successive nodes 180° apart (two ranks)
  opposite,   // decussate: two leaves 180° apart per node, successive pairs turned 90°
  whorled,    // n ≥ 3 leaves per node 360°/n apart, successive whorls turned 180°/n
  spiral,     // one leaf per node, successive nodes turned by the golden angle 137.5°
};

// "alternate" (or "distichous"), "opposite" (or "decussate"), "whorled", "spiral".
std::optional<Phyllotaxis> parse_phyllotaxis(std::string_view name);
const char* phyllotaxis_name(Phyllotaxis mode);

// Leaves at one node: 1 (alternate, spiral), 2 (opposite), per_node (whorled, at least 3).
int leaves_at_node(Phyllotaxis mode, int per_node);

// Azimuth (radians, about the twig, from its reference direction) of leaf j at the twig's
// k-th leaf node. `divergence` (radians) is the spiral's angle between successive nodes.
double phyllotaxis_azimuth(Phyllotaxis mode, int per_node, long k, int j,
                           double divergence = 2.399963229728653);

// The leaf frame rule: the blade axis a (unit), the normal n = normalize(n_opt − (n_opt·a) a)
// where n_opt points from a point z inside the plant to the bud (light comes from outside
// the crown), and the side s = n × a. Orthonormal, n ⊥ a. When n_opt is parallel to a the
// normal falls back to any perpendicular of a.
struct LeafFrame {
  glm::vec3 axis{0.0f, 1.0f, 0.0f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
  glm::vec3 side{1.0f, 0.0f, 0.0f};
};
LeafFrame leaf_frame(glm::vec3 bud, glm::vec3 axis, glm::vec3 inside_point);
LeafFrame leaf_frame_toward(glm::vec3 n_opt, glm::vec3 axis);  // n_opt given directly

// The card's rotation for a leaf frame: card +Y along the axis, +Z along the normal, +X along
// a × n = −s (right-handed).
glm::quat leaf_rotation(const LeafFrame& frame);

// A leaf at `position` whose blade leaves the branch direction `axis` tilted by `tilt`
// radians, at `azimuth` radians around the axis measured from `reference` (a unit vector
// perpendicular to the axis; zero: any_perpendicular(axis)). The blade normal points toward
// `facing` (n_opt) as far as it can while staying perpendicular to the blade. `scale` is the
// blade length. Color is left white.
LeafPlacement orient_leaf(glm::vec3 position, glm::vec3 axis, float azimuth, float tilt,
                          glm::vec3 facing, float scale, glm::vec3 reference = glm::vec3(0.0f));

// A random per-leaf color multiplier: brightness 1 ± jitter and a yellowing of up to jitter
// (more red, less blue). White for jitter 0 (no random draw then).
glm::vec3 leaf_color_variation(Rng& rng, float jitter);

}  // namespace forest
