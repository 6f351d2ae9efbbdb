// Allometric rules of branchings: pipe model, Murray's angles, Holton's strands.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "generators/tree/allometry.h"
#include "generators/methods/lsystem/lsystem.h"
#include "generators/tree/pipe_model.h"

using namespace forest;

namespace {
constexpr double kPi = 3.14159265358979323846;
}

TEST(Allometry, PipeIdentityForEveryExponent) {
  for (double e : {double(kDaVinciExponent), double(kMurrayExponent), double(kUpperExponent)}) {
    std::vector<double> children = {0.3, 0.2, 0.05};
    double r = pipe_parent_radius(children, e);
    double sum = 0.0;
    for (double c : children) sum += std::pow(c, e);
    EXPECT_NEAR(std::pow(r, e), sum, 1e-12) << e;
    EXPECT_GT(r, 0.3);
    // One child: the pipe passes through unchanged.
    EXPECT_NEAR(pipe_parent_radius(std::vector<double>{0.2}, e), 0.2, 1e-15);
  }
  // Higher exponents: thinner parents for the same children.
  std::vector<double> two = {0.1, 0.1};
  EXPECT_GT(pipe_parent_radius(two, 2.0), pipe_parent_radius(two, 2.49));
  EXPECT_GT(pipe_parent_radius(two, 2.49), pipe_parent_radius(two, 3.0));
  EXPECT_EQ(pipe_parent_radius({}, 2.0), 0.0);
}

TEST(Allometry, PipeModelOnAWholeSkeleton) {
  TurtleParams p;
  p.angle_deg = 30.0f;
  TreeGraph g = interpret("F[+F[+F]F]F[-F]F", p, 1);
  for (float e : {kDaVinciExponent, kMurrayExponent, kUpperExponent}) {
    assign_pipe_radii(g, 0.01f, e);
    auto children = children_of(g);
    for (size_t i = 0; i < g.nodes.size(); ++i) {
      if (children[i].empty()) {
        EXPECT_FLOAT_EQ(g.nodes[i].radius, 0.01f);
        continue;
      }
      double sum = 0.0;
      for (uint32_t c : children[i]) sum += std::pow(double(g.nodes[c].radius), double(e));
      EXPECT_NEAR(std::pow(double(g.nodes[i].radius), double(e)), sum, 1e-6 * sum) << i << " " << e;
    }
  }
}

TEST(Allometry, MurrayAnglesThickerChildDeviatesLess) {
  // Radii obeying Murray's law r0³ = r1³ + r2³.
  double r1 = 0.8, r2 = 0.5;
  double r0 = std::cbrt(r1 * r1 * r1 + r2 * r2 * r2);
  BranchAngles a = murray_angles(r0, r1, r2);
  EXPECT_LT(a.alpha1, a.alpha2);
  EXPECT_NEAR(std::cos(a.alpha1), (std::pow(r0, 4) + std::pow(r1, 4) - std::pow(r2, 4)) / (2 * r0 * r0 * r1 * r1), 1e-12);
  EXPECT_NEAR(std::cos(a.alpha2), (std::pow(r0, 4) + std::pow(r2, 4) - std::pow(r1, 4)) / (2 * r0 * r0 * r2 * r2), 1e-12);
  // Symmetric children split symmetrically; swapping them swaps the angles.
  double rs = std::cbrt(2.0) * 0.5;
  BranchAngles s = murray_angles(rs, 0.5, 0.5);
  EXPECT_NEAR(s.alpha1, s.alpha2, 1e-12);
  EXPECT_NEAR(s.alpha1 * 180.0 / kPi, 37.47, 0.05);  // Murray's classic 37.5° for equal children
  BranchAngles w = murray_angles(r0, r2, r1);
  EXPECT_NEAR(w.alpha1, a.alpha2, 1e-12);
  // A vanishing child: the parent goes straight on, the child leaves at a right angle.
  BranchAngles tiny = murray_angles(std::cbrt(1.0 + 1e-9), 1.0, 1e-3);
  EXPECT_NEAR(tiny.alpha1, 0.0, 1e-3);
  EXPECT_GT(tiny.alpha2 * 180.0 / kPi, 85.0);
}

TEST(Allometry, HoltonStrands) {
  BranchAngles h = holton_angles(30.0, 10.0, 1.0);
  EXPECT_NEAR(h.alpha1, 0.25, 1e-12);  // S2 / S0 · A: the child with more strands deviates less
  EXPECT_NEAR(h.alpha1 + h.alpha2, 1.0, 1e-12);
  EXPECT_LT(h.alpha1, h.alpha2);
  EXPECT_NEAR(holton_diameter(0.002, 100.0), 0.02, 1e-12);
  // Strand counts add, so diameters follow the pipe model with exponent 2.
  double d0 = holton_diameter(0.01, 40.0), d1 = holton_diameter(0.01, 30.0), d2 = holton_diameter(0.01, 10.0);
  EXPECT_NEAR(d0 * d0, d1 * d1 + d2 * d2, 1e-12);
}
