// Small graph helpers shared by the image-based methods (particle-flow, visual-hull).
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "generators/methods/common/image_inputs.h"
#include "generators/tree/tree_graph.h"

namespace forest {

// A rooted tree given as parent links in any order (parent[root] = -1) -> TreeGraph with the
// root first and parent < own index (breadth-first order, children in index order). Nodes not
// connected to `root` are dropped; `old_to_new` (optional) receives the mapping (-1 = dropped).
// Cycles cannot survive: only nodes reached from the root are kept.
TreeGraph rooted_tree(const std::vector<glm::dvec3>& positions, const std::vector<int64_t>& parent,
                      size_t root, std::vector<int64_t>* old_to_new = nullptr);

// Branch orders: a node continues its parent's order along the child with the most tips
// below it; the other children start order + 1.
void assign_branch_orders(TreeGraph& graph);

// Removes leaves whose position projects onto background (alpha < 0.5) in some view
// (Neubert 2012 ch5 "drop leaves projecting onto empty mask"; Shlyakhter 2001 step 5).
void drop_leaves_outside_masks(TreeGraph& graph, const ViewSet& set);

// Node 0 is the only root and every parent index is smaller than its child's: one rooted,
// acyclic, connected tree.
bool is_rooted_tree(const TreeGraph& graph);

}  // namespace forest
