// Rotation-minimizing frames by parallel transport (Neubert 2012 ch5, Hanson 1995).
#include <gtest/gtest.h>

#include <cmath>

#include "generators/mesh/bspline.h"
#include "generators/mesh/frames.h"
#include "tests/unit/frame_checks.h"

using namespace forest;

namespace {

// Unit, perpendicular and right-handed: binormal = tangent × normal.
void expect_orthonormal(const Frame& f) { test::expect_right_handed_orthonormal(f.tangent, f.normal, f.binormal); }

// The twist between consecutive frames: the angle between the next normal and the previous
// normal carried over by the minimal rotation (0 for a rotation-minimizing frame).
float twist(const Frame& a, const Frame& b) {
  glm::vec3 carried = transport(a.normal, a.tangent, b.tangent);
  return std::acos(std::clamp(glm::dot(carried, b.normal), -1.0f, 1.0f));
}

// A helix: the Frenet frame turns about the tangent here, the transported one does not.
std::vector<glm::vec3> helix(int n) {
  std::vector<glm::vec3> p;
  for (int i = 0; i < n; ++i) {
    float t = 0.2f * float(i);
    p.emplace_back(std::cos(t), 0.3f * t, std::sin(t));
  }
  return p;
}

}  // namespace

TEST(Frames, OrthonormalWithoutTwist) {
  auto pts = helix(60);
  auto frames = parallel_transport_polyline(pts, glm::vec3(0, 1, 0));
  ASSERT_EQ(frames.size(), pts.size());
  for (const Frame& f : frames) expect_orthonormal(f);
  for (size_t i = 1; i < frames.size(); ++i) EXPECT_LT(twist(frames[i - 1], frames[i]), 1e-3f) << i;
  // The first normal is the requested one, made perpendicular to the tangent.
  glm::vec3 n0 = glm::vec3(0, 1, 0) - glm::dot(glm::vec3(0, 1, 0), frames[0].tangent) * frames[0].tangent;
  EXPECT_NEAR(glm::length(frames[0].normal - glm::normalize(n0)), 0.0f, 1e-5f);
  // Rotation-minimizing: dN/ds has no binormal component, so N_i+1 . B_i is only of second
  // order in the turning angle (0.2 rad per step here).
  for (size_t i = 1; i < frames.size(); ++i)
    EXPECT_NEAR(glm::dot(frames[i].normal, frames[i - 1].binormal), 0.0f, 2e-2f) << i;
}

TEST(Frames, ConstantOnAStraightLine) {
  std::vector<glm::vec3> line;
  for (int i = 0; i < 10; ++i) line.push_back(glm::vec3(1, 2, 3) * float(i) * 0.1f);
  auto frames = parallel_transport_polyline(line);
  for (const Frame& f : frames) {
    expect_orthonormal(f);
    EXPECT_NEAR(glm::length(f.tangent - frames[0].tangent), 0.0f, 1e-6f);  // float rounding only
    EXPECT_NEAR(glm::length(f.normal - frames[0].normal), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(f.binormal - frames[0].binormal), 0.0f, 1e-6f);
  }
  // Coincident points do not break it.
  line.insert(line.begin() + 4, line[4]);
  for (const Frame& f : parallel_transport_polyline(line)) EXPECT_NEAR(glm::length(f.normal - frames[0].normal), 0.0f, 1e-6f);
}

TEST(Frames, NoFlipAtAnInflection) {
  // An S-curve in the xy-plane: the curvature changes sign at the middle. The Frenet normal
  // flips there (it points to the center of curvature); the transported one stays put.
  std::vector<glm::vec4> ctrl = {{0, 0, 0, 1}, {1, 1, 0, 1}, {2, 0, 0, 1}, {3, -1, 0, 1}, {4, 0, 0, 1}};
  BSpline s(ctrl);
  std::vector<glm::vec3> tangents;
  for (int i = 0; i <= 200; ++i) tangents.push_back(s.tangent(s.max_parameter() * i / 200.0));
  auto frames = parallel_transport(tangents, glm::vec3(0, 0, 1));
  for (size_t i = 0; i < frames.size(); ++i) {
    expect_orthonormal(frames[i]);
    // The curve is planar, so the transported normal stays the plane's normal throughout.
    EXPECT_NEAR(glm::dot(frames[i].normal, glm::vec3(0, 0, 1)), 1.0f, 1e-4f) << i;
    if (i > 0) EXPECT_GT(glm::dot(frames[i].normal, frames[i - 1].normal), 0.999f) << i;
  }
  // The Frenet normal flips: its y component changes sign between the two bends.
  auto frenet_y = [&](double t) {
    glm::vec3 d(s.derivative(t)), dd(s.second_derivative(t));
    glm::vec3 n = dd - glm::dot(dd, glm::normalize(d)) * glm::normalize(d);
    return glm::normalize(n).y;
  };
  EXPECT_LT(frenet_y(1.0) * frenet_y(3.0), 0.0f);
}

TEST(Frames, TransportIsTheMinimalRotation) {
  glm::vec3 from(0, 1, 0), to = glm::normalize(glm::vec3(1, 1, 0));
  // The rotation axis (z) is unchanged; x turns like the tangent.
  EXPECT_NEAR(glm::length(transport(glm::vec3(0, 0, 1), from, to) - glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(transport(from, from, to) - to), 0.0f, 1e-6f);
  EXPECT_EQ(transport(glm::vec3(1, 0, 0), from, from), glm::vec3(1, 0, 0));
  // Reversal: a half turn about a perpendicular, lengths kept.
  glm::vec3 v = transport(glm::vec3(1, 0, 0), from, -from);
  EXPECT_NEAR(glm::length(v), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(v, from), 0.0f, 1e-6f);
}
