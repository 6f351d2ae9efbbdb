// Habit metrics of a tree graph: height, crown width, clear bole and the main stem's
// leader, the numbers that tell a spreading broadleaf from an excurrent conifer or a bush
// (`forest measure`). Pure function of the graph: nodes, radii, parents and leaf positions.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "generators/tree/tree_graph.h"

namespace forest {

// A fork of the main stem is codominant when its second largest child is at least this
// fraction of the largest (radius, or subtree size where radii are zero).
inline constexpr float kCodominantRatio = 0.7f;
// The stem must reach this fraction of H before its first codominant fork for a single
// leader (excurrent habit).
inline constexpr float kSingleLeaderFraction = 0.85f;

struct HabitMetrics {
  uint32_t nodes = 0, leaves = 0;
  float base_y = 0;  // the root node's y (m): heights below are measured from it
  float height = 0;  // H: max over nodes of position.y, minus base_y (m)
  // Crown width: extents of the leaf positions along x and along z (m), or of all nodes when
  // the graph has no leaves; `crown_width` is their mean, `crown_ratio` = crown_width / H.
  float crown_width_x = 0, crown_width_z = 0, crown_width = 0, crown_ratio = 0;
  // Height to the crown base (the botanical "height of the lowest live branch"), above
  // base_y (m): every leaf belongs to its nearest node, and that node to the main-stem node
  // its branch leaves the stem from (itself when it is on the stem); the crown base is the
  // lowest such stem node of any leaf. Without leaves: the lowest stem node with a side
  // branch. `clear_bole` = crown_base / H.
  float crown_base = 0, clear_bole = 0;
  // The lowest leaf's y above base_y, ÷ H (a second, simpler crown-base definition).
  float lowest_leaf = 0;
  // Main stem: from the root, at every fork the child with the largest radius (ties: the
  // larger subtree). trunk_height: y above base_y of its first codominant fork, or of its
  // highest node when it has none; trunk_fraction = trunk_height / H.
  uint32_t stem_nodes = 0;
  float trunk_height = 0, trunk_fraction = 0;
  bool codominant_fork = false;  // the stem has one
  // The stem reaches kSingleLeaderFraction · H before (or at) its first codominant fork.
  bool single_leader = false;
};

HabitMetrics measure_habit(const TreeGraph& graph);

// Horizontal extents of points: (max x − min x, max z − min z); zero for no points.
glm::vec2 horizontal_extent(std::span<const glm::vec3> points);

// The main stem's node indices from the root upwards (the rule of HabitMetrics).
std::vector<uint32_t> main_stem(const TreeGraph& graph);

}  // namespace forest
