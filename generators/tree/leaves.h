// Leaf placement on a skeleton (Neubert 2012 ch5 "Twigs and leaves"): along the terminal twigs in
// a phyllotactic pattern and in a cluster at every tip, with random tilt, size and color.
// This is part of the skeleton pass (its randomness lives in TreeGraph::leaves), so meshing
// stays a pure function of the graph.
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

struct LeafParams {
  float size = 0.1f;          // blade length, meters
  float size_jitter = 0.0f;   // size * (1 + jitter * U(-1, 1))
  float angle_deg = 40.0f;    // tilt of the blade away from the twig
  float angle_jitter_deg = 10.0f;
  int per_tip = 1;            // leaves in the cluster at every tip, spread evenly around it
  int along = 0;              // leaf nodes per segment of a terminal twig (see place_twig_leaves)
  Phyllotaxis phyllotaxis = Phyllotaxis::spiral;
  int per_node = 3;           // leaves per node when whorled
  float divergence_deg = 137.5f;  // spiral phyllotaxis
  float color_jitter = 0.0f;  // leaf_color_variation
};

// Appends leaves to graph.leaves. A terminal twig is the path from the last branching node
// to a tip: nodes whose whole subtree is a single path. Each segment of a terminal twig
// carries `along` leaf nodes evenly spaced toward its end node (the last one at the end node
// itself; on a segment that ends at a tip, the tip cluster takes that place), each with
// leaves_at_node leaves turning by the phyllotaxis along the twig from a random start. The
// twig's reference direction is parallel-transported from segment to segment. Blades face
// away from a point inside the crown (the centroid of the leaf-bearing nodes, lowered by a
// quarter of their height range) by the leaf frame rule.
void place_twig_leaves(TreeGraph& graph, const LeafParams& params, uint64_t seed);

}  // namespace forest
