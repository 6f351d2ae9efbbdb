// Branch radii by the pipe model (da Vinci's rule, Neubert 2012 ch5 eq. 5.1 generalized):
// r_parent^Δ = Σ r_child^Δ, with every tip at tip_radius. Δ = 2 is da Vinci's area-preserving
// rule, 2.49 Murray's, 3 the upper end seen in real trees (allometry.h has the constants and
// the per-fork angle rules).
#pragma once
#include "generators/tree/tree_graph.h"

namespace forest {

// Overwrites every node's radius, bottom-up; deterministic. Requires parent < own index.
// A node with one child gets that child's radius (the pipe passes through unchanged).
void assign_pipe_radii(TreeGraph& graph, float tip_radius, float exponent);

}  // namespace forest
