#include "generators/tree/allometry.h"

#include <algorithm>
#include <cmath>

namespace forest {

double pipe_parent_radius(std::span<const double> child_radii, double exponent) {
  double sum = 0.0;
  for (double r : child_radii) sum += std::pow(r, exponent);
  return sum > 0.0 ? std::pow(sum, 1.0 / exponent) : 0.0;
}

BranchAngles murray_angles(double r0, double r1, double r2) {
  const double q0 = r0 * r0 * r0 * r0, q1 = r1 * r1 * r1 * r1, q2 = r2 * r2 * r2 * r2;
  auto angle = [](double c) { return std::acos(std::clamp(c, -1.0, 1.0)); };
  return {angle((q0 + q1 - q2) / (2.0 * r0 * r0 * r1 * r1)),
          angle((q0 + q2 - q1) / (2.0 * r0 * r0 * r2 * r2))};
}

BranchAngles holton_angles(double s1, double s2, double total_angle) {
  double a1 = s2 / (s1 + s2) * total_angle;
  return {a1, total_angle - a1};
}

double holton_diameter(double strand_diameter, double strands) {
  return strand_diameter * std::sqrt(strands);
}

BifurcationSphere bifurcation_sphere(double r1, double r2, double gamma, double min_angle,
                                     double max_angle) {
  BifurcationSphere s;
  s.gamma = std::clamp(gamma, min_angle, max_angle);
  const double sg = std::sin(s.gamma), cg = std::cos(s.gamma);
  // atan2 keeps α in (0, π) when the denominator turns negative (obtuse forks).
  s.alpha = std::atan2(sg, r2 / r1 + cg);
  s.beta = std::atan2(sg, r1 / r2 + cg);
  double sa = std::sin(s.alpha);
  s.radius = sa > 0.0 ? r1 / sa : HUGE_VAL;
  return s;
}

}  // namespace forest
