// Branch axes as uniform cubic B-splines (Neubert 2012 ch5 eq. 5.14):
//   C_k(u) = [u³ u² u 1] · (1/6)[[−1 3 −3 1], [3 −6 3 0], [−3 0 3 0], [1 4 1 0]] · [P_{k−1} P_k P_{k+1} P_{k+2}]ᵀ
// with clamped ends. The source's "open" spline repeats the end control points (⚠): that
// interpolates the ends but with zero speed there, which leaves no tangent for a tube frame.
// We clamp with reflected phantom points P_{−1} = 2P_0 − P_1 and P_n = 2P_{n−1} − P_{n−2}
// [ours]: the curve still starts at P_0 and ends at P_{n−1}, leaves along the first leg of the
// control polygon with non-zero speed and zero curvature, and stays C² everywhere. All
// weights stay ≥ 0, so the curve (and a radius carried in w) stays in the control points'
// convex hull.
#pragma once
#include <vector>

#include <glm/glm.hpp>

namespace forest {

// Blending weights of P_{k−1}, P_k, P_{k+1}, P_{k+2} at u ∈ [0, 1] and their first and second
// derivatives with respect to u. The weights sum to 1 (the derivatives' to 0).
glm::dvec4 bspline_basis(double u);
glm::dvec4 bspline_basis_d1(double u);
glm::dvec4 bspline_basis_d2(double u);

// A clamped uniform cubic B-spline over control points (x, y, z, w); w carries the branch
// radius so that it is smoothed along with the axis. The parameter s runs over [0, n − 1]
// for n control points; segment k covers s ∈ [k, k + 1]; s = k is near (not on) P_k, except
// at the ends, which are interpolated.
class BSpline {
 public:
  BSpline() = default;
  explicit BSpline(std::vector<glm::vec4> control);

  size_t control_count() const { return control_.size(); }
  size_t segments() const { return control_.size() < 2 ? 0 : control_.size() - 1; }
  double max_parameter() const { return double(segments()); }

  // Position (xyz) and radius (w) at s, clamped to [0, max_parameter()].
  glm::vec4 point(double s) const;
  glm::vec4 derivative(double s) const;         // d/ds
  glm::vec4 second_derivative(double s) const;  // d²/ds²
  // Unit tangent of the axis (xyz part); +Y for a degenerate spline.
  glm::vec3 tangent(double s) const;

  // Control point i, i ∈ [−1, n] (the phantom ends included).
  glm::vec4 control(long i) const;

 private:
  glm::vec4 eval(double s, glm::dvec4 (*basis)(double)) const;
  std::vector<glm::vec4> control_;
};

// A point of a sampled spline.
struct SplineSample {
  double s = 0.0;
  glm::vec3 position{0.0f};
  float radius = 0.0f;
  glm::vec3 tangent{0.0f, 1.0f, 0.0f};
};

// Samples s ∈ [s0, s1] adaptively to the curvature: the spline is first sampled densely
// (`substeps` per segment), then a sample is kept only where the tangent has turned more than
// max_bend (radians) since the last kept sample, or the radius has changed by more than
// radius_tolerance (relative). s0 and s1 are always kept. Straight parts get no inner
// samples; the kept tangents of neighbours differ by about max_bend at most.
std::vector<SplineSample> sample_adaptive(const BSpline& spline, double s0, double s1,
                                          double max_bend, double radius_tolerance,
                                          int substeps = 8);

}  // namespace forest
