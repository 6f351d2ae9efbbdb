// Method `silhouettes` (Wither 2009), part 2: branches inferred inside a silhouette.
// B: the branching angle function; C: Hermite branches from the parent axis to each bump;
// D: span-frame shape transfer (over-sketching); E: inferred sub-silhouettes; F: fill-in.
#pragma once
#include <utility>
#include <vector>

#include "generators/methods/silhouettes/silhouettes_skeleton.h"

namespace forest {

// BAF(t), t in [0, 1] along the parent: piecewise linear through its samples (degrees
// between the parent tangent and the branch's start tangent).
struct BranchingAngleFunction {
  std::vector<std::pair<double, double>> samples;  // (t, degrees), sorted by t
  static BranchingAngleFunction linear(double bottom_deg, double top_deg);
  double operator()(double t) const;
  void add_sample(double t, double degrees);  // replaces a sample at the same t
};

struct Branch2D {
  std::vector<glm::dvec2> curve;  // base B ... end E
  Polygon2 crown;                 // its sub-silhouette (may be empty)
  double t = 0.0;                 // base position on the parent axis, [0, 1]
  int side = 1;                   // +1: right of the parent axis (theta_ref 0), -1: left (180)
  glm::dvec2 start_tangent{0, 1}; // unit tangent at B (Hermite m0 / |m0|)
  double end_radius = 0.0;        // inscribed radius of the silhouette at E
  bool filled = false;            // made by the fill-in, not from a bump
  bool sketched = false;          // drawn by the user (over-sketch)
};

// Rotates unit direction `d` by `degrees` counter-clockwise.
glm::dvec2 rotate(glm::dvec2 d, double degrees);

// Step C: the shortest Hermite curve from a sample B_i of the axis (t in [t_lo, 1], n
// samples) to the bump; start tangent = axis tangent rotated by BAF(t_i) toward E, end
// tangent T_E, both of length |E - B_i| / 2.
Branch2D infer_branch(const Polyline2& axis, const Bump& bump, const BranchingAngleFunction& baf,
                      double t_lo = 0.0, int samples = 32);

// Step D: re-expresses `source` (a curve from its base to its end) in the frame of its span
// (end - base) and rebuilds it on the span of `target`, scaled by |span_T| / |span_S|.
std::vector<glm::dvec2> span_transfer(const std::vector<glm::dvec2>& source, glm::dvec2 target_base,
                                      glm::dvec2 target_end);

// Step E: cone angle (degrees) from r / d, linear between 20 and 110 degrees for r / d in
// [0.1, 0.6] [ours: the source gives the angles, not the ratio range], clamped.
double sub_silhouette_cone_deg(double r, double d);
// The parent silhouette's edges inside the cone around [B, E], closed back to B with two
// G1 Hermite curves.
Polygon2 infer_sub_silhouette(const Polygon2& parent, glm::dvec2 base, glm::dvec2 end, double end_radius);

// Step F: walk the axis from bottom to top (`samples` positions from t_lo, each side): copy
// the nearest sibling (by t) and its crown, re-orient by the BAF, scale (1, 0.9, ... 0.3)
// until it fits in the parent silhouette, keep it when at most `max_overlap` of its crown
// overlaps the crowns already there. Returns the added branches.
std::vector<Branch2D> fill_in(const Polyline2& axis, const Polygon2& parent_silhouette,
                              const std::vector<Branch2D>& siblings, const BranchingAngleFunction& baf,
                              double t_lo, int samples, double max_overlap);

}  // namespace forest
