// Method `silhouettes` (Wither 2009), step G: style copy. The branching style of a source
// branch -- its unbranched range (the bare part from its base to the first child), the
// spacing of its branching points along it ~ N(mean, sd) and its BAF (the angles of its
// children, sampled where they sit) -- is measured and applied to other branches: their
// children are re-placed at positions drawn from the source's style, each one a copy of the
// source child nearest in t, turned to the source's BAF at its new place and scaled by the
// ratio of the branch lengths.
#pragma once
#include <functional>
#include <vector>

#include "generators/core/rng.h"
#include "generators/methods/silhouettes/silhouettes_method.h"

namespace forest {

struct BranchingStyle {
  double unbranched = 0.0;    // t of the first child (fraction of the parent's length)
  double spacing_mean = 0.0;  // between consecutive children, fraction of the length
  double spacing_sd = 0.0;
  BranchingAngleFunction baf; // one sample (t, degrees) per child
  size_t children = 0;
};

// The style of a branch from its children (t and start direction against the axis tangent).
BranchingStyle measure_style(const Polyline2& axis, const std::vector<const Branch2D*>& children);

// Child positions t in [unbranched, 1] from the style: the first at the unbranched range,
// then steps ~ N(mean, sd) (at least 2 % of the length); at most `max` positions.
std::vector<double> style_positions(const BranchingStyle& style, Rng& rng, size_t max = 64);

// Copies node `src`'s 2D subtree into h as a new child of `parent` at parameter t of it (the
// copy's root is marked filled, not sketched), every point mapped by `move`; stops when h
// holds max_nodes. Returns the copy's root, or -1 when there was no room.
int copy_subtree(std::vector<SilhouetteNode>& h, int src, int parent, double t,
                 const std::function<glm::dvec2(glm::dvec2)>& move, size_t max_nodes);

// Applies the style of node `source` to every other node of the same level that has
// children (step G on a whole level). Returns the number of branches restyled.
size_t copy_style(std::vector<SilhouetteNode>& h, int source, Rng& rng, size_t max_nodes);

}  // namespace forest
