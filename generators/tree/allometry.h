// Allometry of branchings (Neubert 2012 ch5, "From graphs to models"): how radii and angles of a
// parent and its children relate. The pipe model assigns radii to a whole skeleton
// (pipe_model.h); these are the per-fork rules it and the mesher are built on, available to
// every generator.
#pragma once
#include <span>

namespace forest {

// Diameter exponents Δ of r_parent^Δ = Σ r_child^Δ: da Vinci's area-preserving rule, Murray's
// law (minimum work of a flow, c0^2.49 = c1^2.49 + c2^2.49 in the source) and the upper end
// observed in real trees.
inline constexpr float kDaVinciExponent = 2.0f;
inline constexpr float kMurrayExponent = 2.49f;
inline constexpr float kUpperExponent = 3.0f;

// Pipe model: the parent radius (Σ r_c^Δ)^(1/Δ); 0 for no children. Δ > 0.
double pipe_parent_radius(std::span<const double> child_radii, double exponent);

// Murray's branching angles (radians) of children of radii r1 and r2 off a parent of radius
// r0: cos α1 = (r0⁴ + r1⁴ − r2⁴) / (2 r0² r1²), cos α2 = (r0⁴ + r2⁴ − r1⁴) / (2 r0² r2²).
// The thicker child deviates less from the parent's direction. Cosines are clamped to
// [−1, 1] (radii that do not satisfy Murray's law exactly). Radii > 0.
struct BranchAngles {
  double alpha1 = 0.0;  // deviation of child 1 from the parent direction
  double alpha2 = 0.0;  // deviation of child 2
};
BranchAngles murray_angles(double r0, double r1, double r2);

// Holton's strand model: a parent of S0 = S1 + S2 strands splits its total branching angle A
// (radians) as α1 = (S2 / S0) · A, α2 = A − α1 (the child with more strands deviates less);
// a branch of S strands has diameter t · √S (t: diameter of one strand). S1, S2 > 0.
BranchAngles holton_angles(double s1, double s2, double total_angle);
double holton_diameter(double strand_diameter, double strands);

// Two branches of radii r1, r2 leave a fork at angle γ (radians) between their axes. Their
// inner surfaces meet at distance `radius` from the fork, seen at angle α from axis 1 and β
// from axis 2: β = atan(sin γ / (r1/r2 + cos γ)), α = atan(sin γ / (r2/r1 + cos γ)),
// α + β = γ, radius = r1 / sin α = r2 / sin β ≥ max(r1, r2). Beyond that sphere the two tubes
// are disjoint, so the mesher cuts branches back to it before joining them.
// γ is clamped to [min_angle, max_angle] [ours]: at γ → 0 the tubes never separate
// (radius → ∞); at γ → π with r1 ≠ r2 the "meeting point" lies behind the fork (radius → ∞
// again) although the tubes hardly touch.
struct BifurcationSphere {
  double alpha = 0.0;
  double beta = 0.0;
  double radius = 0.0;
  double gamma = 0.0;  // the clamped angle actually used
};
BifurcationSphere bifurcation_sphere(double r1, double r2, double gamma, double min_angle = 0.0,
                                     double max_angle = 3.141592653589793);

}  // namespace forest
