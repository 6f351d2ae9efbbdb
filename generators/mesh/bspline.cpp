#include "generators/mesh/bspline.h"

#include <algorithm>
#include <cmath>

namespace forest {

glm::dvec4 bspline_basis(double u) {
  const double u2 = u * u, u3 = u2 * u, v = 1.0 - u;
  return glm::dvec4(v * v * v, 3.0 * u3 - 6.0 * u2 + 4.0, -3.0 * u3 + 3.0 * u2 + 3.0 * u + 1.0, u3) / 6.0;
}

glm::dvec4 bspline_basis_d1(double u) {
  const double u2 = u * u, v = 1.0 - u;
  return glm::dvec4(-3.0 * v * v, 9.0 * u2 - 12.0 * u, -9.0 * u2 + 6.0 * u + 3.0, 3.0 * u2) / 6.0;
}

glm::dvec4 bspline_basis_d2(double u) {
  return glm::dvec4(6.0 * (1.0 - u), 18.0 * u - 12.0, -18.0 * u + 6.0, 6.0 * u) / 6.0;
}

BSpline::BSpline(std::vector<glm::vec4> control) : control_(std::move(control)) {}

glm::vec4 BSpline::control(long i) const {
  const long n = long(control_.size());
  if (n == 0) return glm::vec4(0.0f);
  if (n == 1) return control_[0];
  if (i < 0) return 2.0f * control_[0] - control_[1];
  if (i >= n) return 2.0f * control_[size_t(n - 1)] - control_[size_t(n - 2)];
  return control_[size_t(i)];
}

glm::vec4 BSpline::eval(double s, glm::dvec4 (*basis)(double)) const {
  if (control_.size() < 2) return basis == bspline_basis && !control_.empty() ? control_[0] : glm::vec4(0.0f);
  s = std::clamp(s, 0.0, max_parameter());
  long k = std::min(long(s), long(segments()) - 1);
  glm::dvec4 b = basis(s - double(k));
  glm::dvec4 p = b.x * glm::dvec4(control(k - 1)) + b.y * glm::dvec4(control(k)) +
                 b.z * glm::dvec4(control(k + 1)) + b.w * glm::dvec4(control(k + 2));
  return glm::vec4(p);
}

glm::vec4 BSpline::point(double s) const { return eval(s, bspline_basis); }
glm::vec4 BSpline::derivative(double s) const { return eval(s, bspline_basis_d1); }
glm::vec4 BSpline::second_derivative(double s) const { return eval(s, bspline_basis_d2); }

glm::vec3 BSpline::tangent(double s) const {
  glm::vec3 d(derivative(s));
  float len = glm::length(d);
  if (len > 1e-12f) return d / len;
  // Zero speed (coincident control points): fall back to the chord of the segment.
  glm::vec3 chord(point(std::min(s + 1e-3, max_parameter())) - point(std::max(s - 1e-3, 0.0)));
  float cl = glm::length(chord);
  return cl > 1e-12f ? chord / cl : glm::vec3(0.0f, 1.0f, 0.0f);
}

std::vector<SplineSample> sample_adaptive(const BSpline& spline, double s0, double s1,
                                          double max_bend, double radius_tolerance, int substeps) {
  auto sample = [&](double s) {
    glm::vec4 p = spline.point(s);
    return SplineSample{s, glm::vec3(p), p.w, spline.tangent(s)};
  };
  std::vector<SplineSample> out{sample(s0)};
  if (!(s1 > s0)) return out;
  const int n = std::max(1, int(std::ceil((s1 - s0) * double(std::max(substeps, 1)) - 1e-9)));
  std::vector<SplineSample> dense;
  dense.reserve(size_t(n) + 1);
  dense.push_back(out[0]);
  for (int j = 1; j < n; ++j) dense.push_back(sample(s0 + (s1 - s0) * double(j) / double(n)));
  dense.push_back(sample(s1));
  const double cos_bend = std::cos(max_bend);
  for (size_t j = 1; j + 1 < dense.size(); ++j) {
    // Keep j when going on to j + 1 would turn or taper too much since the last kept sample.
    const SplineSample& last = out.back();
    const SplineSample& next = dense[j + 1];
    bool bend = double(glm::dot(last.tangent, next.tangent)) < cos_bend;
    bool taper = std::abs(next.radius - last.radius) > float(radius_tolerance) * last.radius;
    if (bend || taper) out.push_back(dense[j]);
  }
  out.push_back(dense.back());
  return out;
}

}  // namespace forest
