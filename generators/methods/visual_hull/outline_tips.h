// "Interesting points" of a silhouette (Shlyakhter 2001 step 3): branch tips seen in one view, found
// from a hierarchy of convex hulls of the outline (a concavity tree, Sklansky 1972).
//  level 0: the convex hull of the outline. A hull edge is significant when the outline falls
//           back from it by at least `pocket_depth` (a pocket) or when it is long (at least
//           `long_edge` of the hull perimeter: the outline runs far from the hull along it).
//           The hull vertices between two significant edges form one cap (a lobe of the
//           crown); its tip is the outline point of the cap farthest out from the cap's chord.
//  level 1: every deep pocket is a polygon of empty space (its outline chain closed by the
//           hull edge). Its own convex hull has edges the chain falls back from: those are parts
//           of the tree poking into the pocket (a smaller lobe inside a notch) ...
//  level 2: ... and the point of such a part farthest from its hull edge is a tip. A part that
//           starts at the pocket's rim (an end of its chain) is the flank of the lobe next to
//           the pocket bulging into it, not a new lobe, and is skipped.
//  Deeper levels alternate the same way (pockets of protrusions, their protrusions, ...).
// The cap at the tree's foot (the one holding an end of the hull edge nearest to the projected
// trunk base) is the trunk, not a tip.
#pragma once
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "generators/methods/common/image_inputs.h"

namespace forest {

struct OutlineTipParams {
  double pocket_depth = 0.08;   // of sqrt(silhouette area), pixels below which a pocket is noise
  double long_edge = 0.12;      // of the hull perimeter
  int max_level = 4;            // deepest level of the hierarchy visited (0, 2, 4, ... give tips)
  double min_separation = 0.05; // of the mask diagonal, between two tips
};

struct OutlineTip {
  glm::dvec2 pixel{0.0};  // pixel centre on the outline
  int level = 0;          // 0: a cap of the outline's hull; 2, 4: protrusions inside pockets
  double depth = 0.0;     // pixels: the deepest adjacent pocket (level 0) or the protrusion's height
};

// Outer outline of the largest 8-connected silhouette component, as pixel centres in order
// (Moore-neighbour tracing, clockwise on screen); empty for an empty mask.
std::vector<glm::dvec2> trace_outline(const Mask& mask);

// Tips of one mask, best first (lower level first, then deeper pocket); `base` is the trunk
// foot in pixels when known. At most `count` tips (count < 0: all).
std::vector<OutlineTip> outline_tips(const Mask& mask, const OutlineTipParams& params,
                                     std::optional<glm::dvec2> base = std::nullopt, int count = -1);

}  // namespace forest
