// L-system rewriting, turtle interpretation, pipe-model radii and leaf placement.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include <glm/gtc/quaternion.hpp>

#include "generators/core/input_error.h"
#include "generators/tree/leaves.h"
#include "generators/methods/lsystem/lsystem.h"
#include "generators/tree/pipe_model.h"

using namespace forest;

namespace {

LSystem fig2_1() {
  return LSystem{"X", {{'X', "F[[X]-X]F[+FX]-X", 1.0}, {'F', "FF", 1.0}}};
}

size_t count(const std::string& s, char c) { return size_t(std::count(s.begin(), s.end(), c)); }

// Independent reference for deterministic systems: one production per letter.
std::string naive_rewrite(std::string s, const std::map<char, std::string>& rules, int n) {
  for (int i = 0; i < n; ++i) {
    std::string next;
    for (char c : s) {
      auto it = rules.find(c);
      next += it == rules.end() ? std::string(1, c) : it->second;
    }
    s = next;
  }
  return s;
}

TurtleParams unit_turtle(float angle = 90.0f) {
  TurtleParams p;
  p.angle_deg = angle;
  p.step = 1.0f;
  return p;
}

void expect_near(glm::vec3 a, glm::vec3 b, float eps = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

}  // namespace

TEST(LSystemRewrite, DoublingGivesPowerOfTwo) {
  LSystem s{"F", {{'F', "FF", 1.0}}};
  for (int n = 0; n <= 10; ++n) EXPECT_EQ(rewrite(s, n, 1), std::string(size_t(1) << n, 'F'));
}

TEST(LSystemRewrite, Fig2_1ExactStringsAndCounts) {
  LSystem s = fig2_1();
  EXPECT_EQ(rewrite(s, 1, 1), "F[[X]-X]F[+FX]-X");
  EXPECT_EQ(rewrite(s, 2, 1), "FF[[F[[X]-X]F[+FX]-X]-F[[X]-X]F[+FX]-X]FF[+FFF[[X]-X]F[+FX]-X]-"
                              "F[[X]-X]F[+FX]-X");
  std::map<char, std::string> rules{{'X', "F[[X]-X]F[+FX]-X"}, {'F', "FF"}};
  EXPECT_EQ(rewrite(s, 5, 1), naive_rewrite("X", rules, 5));
  // Closed-form counts for n = 7: X_n = 4 X_{n-1}, F_n = 2 F_{n-1} + 3 X_{n-1},
  // [_n = [_{n-1} + 3 X_{n-1}, -_n = -_{n-1} + 2 X_{n-1}, +_n = +_{n-1} + X_{n-1}.
  uint64_t X = 1, F = 0, open = 0, minus = 0, plus = 0;
  for (int i = 0; i < 7; ++i) {
    F = 2 * F + 3 * X;
    open += 3 * X;
    minus += 2 * X;
    plus += X;
    X *= 4;
  }
  std::string r = rewrite(s, 7, 1);
  EXPECT_EQ(count(r, 'X'), X);
  EXPECT_EQ(count(r, 'F'), F);
  EXPECT_EQ(F, 24384u);
  EXPECT_EQ(count(r, '['), open);
  EXPECT_EQ(count(r, ']'), open);
  EXPECT_EQ(count(r, '-'), minus);
  EXPECT_EQ(count(r, '+'), plus);
  EXPECT_EQ(r.size(), X + F + 2 * open + minus + plus);
}

TEST(LSystemRewrite, ArgumentsAreNotRewritten) {
  LSystem s{"F(2)+(30)A", {{'A', "F(0.5)A", 1.0}}};
  EXPECT_EQ(rewrite(s, 2, 1), "F(2)+(30)F(0.5)F(0.5)A");
}

TEST(LSystemRewrite, ExplosionIsAnInputError) {
  LSystem s{"F", {{'F', "FF", 1.0}}};
  EXPECT_THROW(rewrite(s, 40, 1), InputError);
  EXPECT_NO_THROW(rewrite(s, 20, 1));  // 1 M symbols: within the limit
  EXPECT_THROW(rewrite(s, 21, 1, 1'000'000), InputError);
  LSystem bad{"A", {{'+', "FF", 1.0}}};
  EXPECT_THROW(rewrite(bad, 1, 1), InputError);  // predecessors are letters
}

TEST(LSystemRewrite, StochasticChoiceIsDeterministicAndSeedDependent) {
  LSystem s{"A", {{'A', "F[+A]A", 1.0}, {'A', "F[-A]FA", 1.0}, {'A', "FA", 0.5}}};
  EXPECT_EQ(rewrite(s, 6, 42), rewrite(s, 6, 42));
  EXPECT_NE(rewrite(s, 6, 42), rewrite(s, 6, 43));
}

TEST(LSystemRewrite, WeightsAreRespected) {
  LSystem s{std::string(200, 'A'), {{'A', "B", 3.0}, {'A', "C", 1.0}}};
  size_t b = 0, total = 0;
  for (uint64_t seed = 0; seed < 100; ++seed) {
    std::string r = rewrite(s, 1, seed);
    b += count(r, 'B');
    total += r.size();
    EXPECT_EQ(count(r, 'B') + count(r, 'C'), r.size());
  }
  // 20000 draws of p = 0.75: standard deviation 0.003; allow about 5 sigma.
  EXPECT_NEAR(double(b) / double(total), 0.75, 0.015);
}

TEST(LSystemSyntax, BracketsAndArguments) {
  EXPECT_FALSE(check_lsystem_syntax("F[+F[-F]F]F(0.5)+(30)!(0.8)"));
  EXPECT_TRUE(check_lsystem_syntax("F[F"));
  EXPECT_TRUE(check_lsystem_syntax("F]F["));
  EXPECT_TRUE(check_lsystem_syntax("X(2)"));
  EXPECT_TRUE(check_lsystem_syntax("F(abc)"));
  EXPECT_TRUE(check_lsystem_syntax("F(1"));
  EXPECT_TRUE(check_lsystem_syntax("F)"));
  EXPECT_THROW(interpret("F[F", unit_turtle(), 1), InputError);
  EXPECT_THROW(interpret("F]F", unit_turtle(), 1), InputError);
}

TEST(Turtle, NodePerFParentsAndOrders) {
  TreeGraph g = interpret("F[F[F]F]F", unit_turtle(), 1);
  ASSERT_EQ(g.nodes.size(), 6u);  // root + 5 F
  std::vector<int32_t> parents{-1, 0, 1, 2, 2, 1};
  std::vector<uint32_t> orders{0, 0, 1, 2, 1, 0};
  for (size_t i = 0; i < g.nodes.size(); ++i) {
    EXPECT_EQ(g.nodes[i].parent, parents[i]) << i;
    EXPECT_EQ(g.nodes[i].order, orders[i]) << i;
  }
  // A big system: node count = F count + 1, parent < own index.
  std::string s = rewrite(fig2_1(), 5, 1);
  TreeGraph big = interpret(s, unit_turtle(22.5f), 1);
  EXPECT_EQ(big.nodes.size(), count(s, 'F') + 1);
  for (size_t i = 1; i < big.nodes.size(); ++i) EXPECT_LT(big.nodes[i].parent, int32_t(i));
}

TEST(Turtle, Geometry) {
  TreeGraph g = interpret("F+F", unit_turtle(), 1);
  expect_near(g.nodes[1].position, {0, 1, 0});
  expect_near(g.nodes[2].position, {-1, 1, 0});  // + turns toward the turtle's left (-X)
  g = interpret("F&F", unit_turtle(), 1);
  expect_near(g.nodes[2].position, {0, 1, -1});  // & pitches down, away from up (+Z)
  g = interpret("F^F", unit_turtle(), 1);
  expect_near(g.nodes[2].position, {0, 1, 1});
  g = interpret("F\\+F", unit_turtle(), 1);  // roll 90 first: left becomes +Z
  expect_near(g.nodes[2].position, {0, 1, 1});
  g = interpret("FfF", unit_turtle(), 1);
  ASSERT_EQ(g.nodes.size(), 3u);
  expect_near(g.nodes[2].position, {0, 3, 0});
  EXPECT_EQ(g.nodes[2].parent, 1);
  g = interpret("F|F", unit_turtle(), 1);
  expect_near(g.nodes[2].position, {0, 0, 0});
  g = interpret("F!(0.5)F+(45)F(2)", unit_turtle(), 1);
  expect_near(g.nodes[2].position, {0, 1.5f, 0});
  float d = std::sqrt(0.5f);  // 2 * 0.5 step at 45 degrees
  expect_near(g.nodes[3].position, {-d, 1.5f + d, 0});
  g = interpret("F[+F]F", unit_turtle(), 1);  // pop restores position and heading
  expect_near(g.nodes[3].position, {0, 2, 0});
  EXPECT_EQ(g.nodes[3].parent, 1);
}

TEST(Turtle, TropismBendsTowardItsDirection) {
  TurtleParams p = unit_turtle();
  p.tropism = {1, 0, 0};
  p.tropism_strength = 0.2f;
  TreeGraph g = interpret("FFFFFFFFFF", p, 1);
  float prev_dx = 0.0f;
  for (size_t i = 2; i < g.nodes.size(); ++i) {
    glm::vec3 d = g.nodes[i].position - g.nodes[i - 1].position;
    EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
    EXPECT_GT(d.x, prev_dx);  // turning ever more toward +X
    prev_dx = d.x;
  }
  // A vertical stem under gravity tropism stays straight.
  p.tropism = {0, -1, 0};
  g = interpret("FFFFF", p, 1);
  expect_near(g.nodes.back().position, {0, 5, 0});
}

TEST(Turtle, JitterIsSeededAndBounded) {
  TurtleParams p = unit_turtle(30.0f);
  p.angle_jitter_deg = 10.0f;
  p.step_jitter = 0.2f;
  p.roll_jitter_deg = 180.0f;
  std::string s = rewrite(fig2_1(), 3, 1);
  TreeGraph a = interpret(s, p, 5), b = interpret(s, p, 5), c = interpret(s, p, 6);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  bool differs = false;
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    EXPECT_EQ(a.nodes[i].position, b.nodes[i].position);
    differs = differs || a.nodes[i].position != c.nodes[i].position;
    if (i > 0) {
      float len = glm::length(a.nodes[i].position - a.nodes[size_t(a.nodes[i].parent)].position);
      EXPECT_GE(len, 0.8f - 1e-5f);
      EXPECT_LE(len, 1.2f + 1e-5f);
    }
  }
  EXPECT_TRUE(differs);
  bool off_plane = false;  // roll jitter makes the planar figure 3D
  for (const TreeNode& n : a.nodes) off_plane = off_plane || std::abs(n.position.z) > 1e-3f;
  EXPECT_TRUE(off_plane);
}

TEST(PipeModel, DaVinciRuleAtEveryNode) {
  std::string s = rewrite(fig2_1(), 4, 1);
  for (float e : {2.0f, 2.49f, 3.0f}) {
    TreeGraph g = interpret(s, unit_turtle(22.5f), 1);
    assign_pipe_radii(g, 0.01f, e);
    auto children = children_of(g);
    size_t branchings = 0;
    for (size_t i = 0; i < g.nodes.size(); ++i) {
      if (children[i].empty()) {
        EXPECT_FLOAT_EQ(g.nodes[i].radius, 0.01f);
        continue;
      }
      double sum = 0.0;
      for (uint32_t c : children[i]) sum += std::pow(double(g.nodes[c].radius), double(e));
      EXPECT_NEAR(std::pow(double(g.nodes[i].radius), double(e)), sum, 1e-4 * sum) << i;
      branchings += children[i].size() > 1;
    }
    EXPECT_GT(branchings, 10u);
    // The rule conserves sum(r^e) down the tree: the root carries all tips.
    size_t tips = 0;
    for (auto& c : children) tips += c.empty();
    EXPECT_NEAR(g.nodes[0].radius, 0.01 * std::pow(double(tips), 1.0 / e), 1e-4);
  }
}

TEST(ChildrenOf, InverseOfParent) {
  TreeGraph g = interpret("F[F][F]F", unit_turtle(), 1);
  auto c = children_of(g);
  ASSERT_EQ(c.size(), 5u);
  EXPECT_EQ(c[0], std::vector<uint32_t>({1}));
  EXPECT_EQ(c[1], std::vector<uint32_t>({2, 3, 4}));
  EXPECT_TRUE(c[2].empty());
}

TEST(Leaves, LSymbolsPlaceLeavesAtTheTurtle) {
  TurtleParams p = unit_turtle();
  p.leaf_size = 0.3f;
  TreeGraph g = interpret("F[+FL]FL", p, 1);
  ASSERT_EQ(g.leaves.size(), 2u);
  expect_near(g.leaves[0].position, {-1, 1, 0});
  expect_near(g.leaves[1].position, {0, 2, 0});
  EXPECT_FLOAT_EQ(g.leaves[0].scale, 0.3f);
}
