// MGV, the method with guiding vectors (Xu 2015 ch5, Xu & Mould 2015): one Yao-8 graph over
// Poisson nodes in a box; each iteration runs a multi-source Dijkstra from the whole tree in
// which finalizing a node fixes its guiding vector (the parent's, rotated by α(h) about
// up × g) and then its out-edge weights w = d (1 − ê·v) ∈ [0, 2d]; endpoints are chosen and
// their least-cost paths join the tree. Iteration 1 is usually the trunk (one endpoint,
// α = 0), iteration 2 draws Poisson endpoints in a crown volume, later ones pick nodes exactly
// k hops from the tree, the outermost fraction t by hop count from the root.
#pragma once
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/glm.hpp>

#include "generators/methods/common/graph_volume.h"
#include "generators/methods/common/graph_yao.h"
#include "generators/tree/tree_graph.h"

namespace forest {

enum class AlphaRule {
  Piecewise,  // eq. 5.1: α1 if h ≤ h0 else α2 (α1 optionally random per source node)
  Axis,       // eq. 5.2: α = θ √(β/π), β = ∠(node position − root, up)
  Height,     // Table 6.1 (e), (i): α1 = 180° (1 − y/H) for h ≤ h0, else α2
};
enum class EndpointSelect { Point, Volume, Hops };
enum class EndpointPolicy { Any, Hanging, Upright };  // endpoint lower / higher than its source

struct MgvIteration {
  EndpointSelect select = EndpointSelect::Hops;
  glm::vec3 point{0.0f};        // Point: the reached node nearest this
  std::vector<Shape> volume;    // Volume: Poisson endpoints in this union
  size_t endpoints = 100;
  uint32_t hops = 4;            // Hops: k
  float outer = 0.6f;           // Hops: t, the outermost fraction kept
  AlphaRule rule = AlphaRule::Piecewise;
  float alpha1 = 0.0f, alpha2 = 0.0f;  // radians, + bends away from up (down / outward)
  uint32_t h0 = 1;
  bool alpha1_random = false;   // α1 ~ U(alpha1_lo, alpha1_hi) per source node (Fig. 5.5 c)
  float alpha1_lo = 0.0f, alpha1_hi = 0.0f;
  float theta = 0.0f;           // Axis rule
  EndpointPolicy policy = EndpointPolicy::Any;
  // [ours] Only tree nodes at least this high (m above the root) are sources of this
  // iteration's paths, so no branch of it leaves the stem lower: a clear bole, and the fork
  // of a broadleaf's trunk at a chosen height. -inf: the whole tree, as in the thesis.
  float sources_above = -std::numeric_limits<float>::infinity();
};

struct MgvParams {
  glm::vec3 size{10.0f, 12.0f, 10.0f};  // box: x and z centred on the root, y from the root up
  size_t nodes = 30000;
  float reach = 4.0f;                    // longest Yao edge in node spacings
  std::vector<MgvIteration> iterations;
};

// The graph can be reused across trees of one box (the thesis' interactive setting).
struct MgvGraph {
  YaoGraph graph;
  uint32_t root = 0;   // node 0: bottom centre
  float spacing = 0.0f;
};

MgvGraph build_mgv_graph(const MgvParams& params, uint64_t seed);

// Guiding vector of a node: `parent_guide` rotated by `alpha` about up × parent_guide, or
// about up × edge when parent_guide is vertical; unchanged when both are vertical.
glm::vec3 rotate_guide(glm::vec3 parent_guide, glm::vec3 edge_dir, float alpha);

// w_E = d_E (1 − ê_E · v_E), with ê the unit edge direction and v the unit guiding vector.
inline float guided_weight(float length, glm::vec3 edge_unit, glm::vec3 guide) {
  return length * (1.0f - glm::dot(edge_unit, guide));
}

struct MgvStats {
  size_t endpoints = 0;
  std::vector<size_t> endpoints_per_iteration;
  std::vector<glm::vec3> guides;  // final guiding vector of every graph node (zero = never set)
  std::vector<int32_t> tree_node; // graph node -> tree node (-1 outside the tree)
};

TreeGraph grow_mgv(const MgvGraph& graph, const MgvParams& params, uint64_t seed,
                   MgvStats* stats = nullptr);

}  // namespace forest
