// Leaf placement on a skeleton: at branch tips and along the terminal twigs, with random
// azimuth, tilt and size. This is part of the skeleton pass (its randomness lives in
// TreeGraph::leaves), so meshing stays a pure function of the graph.
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

#include "generators/tree/tree_graph.h"

namespace forest {

// A leaf at `position` whose blade leaves the branch direction `axis` tilted by `tilt`
// radians, at `azimuth` radians around the axis. The blade normal (+Z of the card) points
// toward `facing` as far as it can while staying perpendicular to the blade (seed 000 ch5:
// n = normalize(n_opt - (n_opt . a) a)). `scale` is the blade length.
LeafPlacement orient_leaf(glm::vec3 position, glm::vec3 axis, float azimuth, float tilt,
                          glm::vec3 facing, float scale);

struct LeafParams {
  float size = 0.1f;          // blade length, meters
  float size_jitter = 0.0f;   // size * (1 + jitter * U(-1, 1))
  float angle_deg = 40.0f;    // tilt of the blade away from the twig
  float angle_jitter_deg = 10.0f;
  int per_tip = 1;            // leaves at every terminal node
  int along = 0;              // leaves at every other node of a terminal twig
};

// Appends leaves to graph.leaves. A terminal twig is the path from the last branching node
// to a tip: nodes whose whole subtree is a single path. Blades face away from the centroid
// of the skeleton (light comes from outside the crown).
void place_twig_leaves(TreeGraph& graph, const LeafParams& params, uint64_t seed);

}  // namespace forest
