// Uniform cubic B-splines with clamped ends (Neubert 2012 ch5 eq. 5.14) and their adaptive sampling.
#include <gtest/gtest.h>

#include <cmath>

#include "generators/mesh/bspline.h"

using namespace forest;

namespace {

BSpline wiggle() {
  return BSpline({{0, 0, 0, 0.5f}, {1, 2, 0, 0.4f}, {3, 2, 1, 0.3f}, {4, 0, 2, 0.25f}, {6, 1, 2, 0.1f},
                  {7, 3, 1, 0.05f}});
}

void expect_near(glm::vec4 a, glm::vec4 b, float tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
  EXPECT_NEAR(a.w, b.w, tol);
}

}  // namespace

TEST(BSpline, BasisIsAPartitionOfUnityAndNonNegative) {
  for (int i = 0; i <= 100; ++i) {
    double u = i / 100.0;
    glm::dvec4 b = bspline_basis(u);
    EXPECT_NEAR(b.x + b.y + b.z + b.w, 1.0, 1e-12);
    EXPECT_GE(std::min({b.x, b.y, b.z, b.w}), 0.0);
    glm::dvec4 d1 = bspline_basis_d1(u), d2 = bspline_basis_d2(u);
    EXPECT_NEAR(d1.x + d1.y + d1.z + d1.w, 0.0, 1e-12);
    EXPECT_NEAR(d2.x + d2.y + d2.z + d2.w, 0.0, 1e-12);
  }
  // The matrix of eq. 5.14 at u = 0: (1, 4, 1, 0) / 6.
  glm::dvec4 b0 = bspline_basis(0.0);
  EXPECT_NEAR(b0.x, 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(b0.y, 4.0 / 6.0, 1e-15);
  EXPECT_NEAR(b0.z, 1.0 / 6.0, 1e-15);
  EXPECT_EQ(b0.w, 0.0);
  // Derivatives agree with finite differences of the basis.
  for (double u : {0.1, 0.5, 0.9}) {
    const double h = 1e-6;
    glm::dvec4 fd = (bspline_basis(u + h) - bspline_basis(u - h)) / (2 * h);
    glm::dvec4 fd2 = (bspline_basis_d1(u + h) - bspline_basis_d1(u - h)) / (2 * h);
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR(fd[k], bspline_basis_d1(u)[k], 1e-8);
      EXPECT_NEAR(fd2[k], bspline_basis_d2(u)[k], 1e-7);
    }
  }
}

TEST(BSpline, C2AcrossSegments) {
  BSpline s = wiggle();
  ASSERT_EQ(s.segments(), 5u);
  for (int k = 1; k < 5; ++k) {
    // Left limit (end of segment k - 1) against the start of segment k.
    const double eps = 1e-9;
    expect_near(s.point(k - eps), s.point(k), 1e-5f);
    expect_near(s.derivative(k - eps), s.derivative(k), 1e-5f);
    expect_near(s.second_derivative(k - eps), s.second_derivative(k), 1e-4f);
  }
}

TEST(BSpline, ClampedEndsInterpolateWithTheFirstLegAsTangent) {
  BSpline s = wiggle();
  expect_near(s.point(0.0), glm::vec4(0, 0, 0, 0.5f), 1e-6f);
  expect_near(s.point(s.max_parameter()), glm::vec4(7, 3, 1, 0.05f), 1e-6f);
  glm::vec3 t0 = s.tangent(0.0), t1 = s.tangent(s.max_parameter());
  EXPECT_NEAR(glm::dot(t0, glm::normalize(glm::vec3(1, 2, 0))), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(t1, glm::normalize(glm::vec3(1, 2, -1))), 1.0f, 1e-6f);
  // Non-zero speed (the phantom-point clamp), zero curvature at the ends.
  EXPECT_GT(glm::length(glm::vec3(s.derivative(0.0))), 0.5f);
  EXPECT_NEAR(glm::length(glm::vec3(s.second_derivative(0.0))), 0.0f, 1e-5f);
  // Out-of-range parameters clamp.
  expect_near(s.point(-1.0), s.point(0.0), 0.0f);
  expect_near(s.point(99.0), s.point(s.max_parameter()), 0.0f);
}

TEST(BSpline, InteriorIsTheSmoothedControlPolygon) {
  BSpline s = wiggle();
  // s = k is (P_{k-1} + 4 P_k + P_{k+1}) / 6 inside; the radius stays within its controls.
  for (int k = 1; k < 5; ++k)
    expect_near(s.point(k), (s.control(k - 1) + 4.0f * s.control(k) + s.control(k + 1)) / 6.0f, 1e-5f);
  for (int i = 0; i <= 100; ++i) {
    float r = s.point(5.0 * i / 100.0).w;
    EXPECT_GE(r, 0.05f - 1e-6f);
    EXPECT_LE(r, 0.5f + 1e-6f);
  }
  // Two points: a straight segment.
  BSpline line({{0, 0, 0, 1}, {0, 2, 0, 1}});
  expect_near(line.point(0.5), glm::vec4(0, 1, 0, 1), 1e-6f);
  EXPECT_NEAR(glm::length(line.tangent(0.3) - glm::vec3(0, 1, 0)), 0.0f, 1e-6f);
}

TEST(BSpline, AdaptiveSamplingFollowsCurvature) {
  // Straight: only the ends.
  BSpline straight({{0, 0, 0, 1}, {0, 1, 0, 1}, {0, 2, 0, 1}, {0, 3, 0, 1}});
  auto a = sample_adaptive(straight, 0.0, 3.0, 0.2, 0.1);
  ASSERT_EQ(a.size(), 2u);
  EXPECT_EQ(a.front().s, 0.0);
  EXPECT_EQ(a.back().s, 3.0);
  // A quarter circle: about (90° / max bend) samples, neighbours within ~max bend.
  std::vector<glm::vec4> arc;
  for (int i = 0; i <= 8; ++i) {
    double t = 1.5707963 * i / 8.0;
    arc.emplace_back(std::cos(t), std::sin(t), 0.0f, 0.1f);
  }
  BSpline curve(arc);
  const double bend = 10.0 * 3.14159265 / 180.0;
  auto b = sample_adaptive(curve, 0.0, curve.max_parameter(), bend, 0.1, 16);
  EXPECT_GE(b.size(), 8u);
  EXPECT_LE(b.size(), 14u);
  for (size_t i = 1; i < b.size(); ++i) {
    EXPECT_GT(b[i].s, b[i - 1].s);
    EXPECT_LE(std::acos(std::min(1.0f, glm::dot(b[i].tangent, b[i - 1].tangent))), bend * 1.2);
  }
  // Tighter bends: more samples.
  EXPECT_GT(sample_adaptive(curve, 0.0, curve.max_parameter(), bend / 2, 0.1, 16).size(), b.size());
  // A taper alone also adds samples.
  BSpline taper({{0, 0, 0, 1.0f}, {0, 1, 0, 0.5f}, {0, 2, 0, 0.25f}});
  EXPECT_GT(sample_adaptive(taper, 0.0, 2.0, 0.2, 0.1).size(), 3u);
}
