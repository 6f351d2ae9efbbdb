// Leaves: phyllotaxis, the leaf frame rule, per-leaf color, the leaf texture and card.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "generators/core/input_error.h"
#include "generators/species/registry.h"
#include "generators/mesh/frames.h"
#include "generators/mesh/leaf_texture.h"
#include "generators/tree/leaves.h"
#include "generators/methods/lsystem/lsystem.h"
#include "generators/mesh/mesher.h"
#include "tests/unit/frame_checks.h"

using namespace forest;

namespace {

constexpr double kPi = 3.14159265358979323846;

TreeGraph straight_twig(int segments) {
  TurtleParams p;
  p.step = 1.0f;
  return interpret(std::string(size_t(segments), 'F'), p, 1);
}

// Azimuth of a leaf's blade about the +Y twig, in [0, 2π).
double azimuth_of(const LeafPlacement& l, glm::vec3 reference) {
  glm::vec3 blade = l.rotation * glm::vec3(0, 1, 0);
  glm::vec3 q = glm::cross(glm::vec3(0, 1, 0), reference);
  double a = std::atan2(double(glm::dot(blade, q)), double(glm::dot(blade, reference)));
  return a < 0 ? a + 2 * kPi : a;
}

double angle_diff(double a, double b) {
  double d = std::fmod(std::abs(a - b), 2 * kPi);
  return std::min(d, 2 * kPi - d);
}

}  // namespace

TEST(Leaves, LeafFrameIsOrthonormalWithNormalPerpendicularToTheAxis) {
  for (glm::vec3 axis : {glm::vec3(0, 1, 0), glm::vec3(1, 2, 3), glm::vec3(-1, 0, 0.2f)})
    for (glm::vec3 bud : {glm::vec3(1, 5, 0), glm::vec3(-2, 1, 3), glm::vec3(0, 9, 0)}) {
      glm::vec3 z(0, 3, 0);
      LeafFrame f = leaf_frame(bud, axis, z);
      test::expect_right_handed_orthonormal(f.normal, f.axis, f.side);  // s = n × a
      // n is n_opt (from z to the bud) with its axial part removed.
      glm::vec3 n_opt = glm::normalize(bud - z);
      glm::vec3 expect = n_opt - glm::dot(n_opt, f.axis) * f.axis;
      if (glm::length(expect) > 1e-3f) {
        EXPECT_NEAR(glm::length(f.normal - glm::normalize(expect)), 0.0f, 1e-5f);
      }
      // The card rotation maps +Y to a, +Z to n.
      glm::quat q = leaf_rotation(f);
      EXPECT_NEAR(glm::length(q * glm::vec3(0, 1, 0) - f.axis), 0.0f, 1e-5f);
      EXPECT_NEAR(glm::length(q * glm::vec3(0, 0, 1) - f.normal), 0.0f, 1e-5f);
      EXPECT_NEAR(glm::length(q * glm::vec3(1, 0, 0) + f.side), 0.0f, 1e-5f);
    }
  // n_opt along the axis: still a valid frame.
  LeafFrame f = leaf_frame(glm::vec3(0, 2, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 0));
  EXPECT_NEAR(glm::dot(f.normal, f.axis), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(f.normal), 1.0f, 1e-6f);
}

TEST(Leaves, PhyllotaxisModes) {
  EXPECT_EQ(parse_phyllotaxis("distichous"), Phyllotaxis::alternate);
  EXPECT_EQ(parse_phyllotaxis("decussate"), Phyllotaxis::opposite);
  EXPECT_EQ(parse_phyllotaxis("whorled"), Phyllotaxis::whorled);
  EXPECT_EQ(parse_phyllotaxis("spiral"), Phyllotaxis::spiral);
  EXPECT_FALSE(parse_phyllotaxis("random").has_value());
  EXPECT_EQ(leaves_at_node(Phyllotaxis::alternate, 5), 1);
  EXPECT_EQ(leaves_at_node(Phyllotaxis::opposite, 5), 2);
  EXPECT_EQ(leaves_at_node(Phyllotaxis::whorled, 5), 5);
  EXPECT_EQ(leaves_at_node(Phyllotaxis::whorled, 1), 3);
  EXPECT_EQ(leaves_at_node(Phyllotaxis::spiral, 5), 1);
  // Alternate: 180° between nodes. Opposite: pairs 180° apart, pairs turned 90°.
  EXPECT_NEAR(angle_diff(phyllotaxis_azimuth(Phyllotaxis::alternate, 1, 1, 0), 0.0), kPi, 1e-12);
  EXPECT_NEAR(angle_diff(phyllotaxis_azimuth(Phyllotaxis::opposite, 2, 0, 1), 0.0), kPi, 1e-12);
  EXPECT_NEAR(angle_diff(phyllotaxis_azimuth(Phyllotaxis::opposite, 2, 1, 0), 0.0), kPi / 2, 1e-12);
  // Whorled with 4: 90° inside a whorl, whorls turned 45°.
  EXPECT_NEAR(angle_diff(phyllotaxis_azimuth(Phyllotaxis::whorled, 4, 0, 1), 0.0), kPi / 2, 1e-12);
  EXPECT_NEAR(angle_diff(phyllotaxis_azimuth(Phyllotaxis::whorled, 4, 1, 0), 0.0), kPi / 4, 1e-12);
  // Spiral: the golden angle.
  EXPECT_NEAR(phyllotaxis_azimuth(Phyllotaxis::spiral, 1, 3, 0), 3 * 137.50776 * kPi / 180.0, 1e-4);
}

TEST(LeafTexture, AlphaMaskedAndDeterministic) {
  for (LeafShape shape : kLeafShapes) {
    Image8 t = make_leaf_texture(shape, 128);
    ASSERT_EQ(t.width, 128u);
    ASSERT_EQ(t.height, 128u);
    ASSERT_EQ(t.rgba.size(), 128u * 128u * 4u);
    size_t clear = 0, opaque = 0, partial = 0;
    for (size_t i = 3; i < t.rgba.size(); i += 4) {
      clear += t.rgba[i] == 0;
      opaque += t.rgba[i] == 255;
      partial += t.rgba[i] > 0 && t.rgba[i] < 255;
    }
    EXPECT_GT(clear, 1000u) << leaf_shape_name(shape);
    EXPECT_GT(opaque, 1000u) << leaf_shape_name(shape);
    EXPECT_GT(partial, 50u) << leaf_shape_name(shape);  // antialiased edge
    EXPECT_EQ(make_leaf_texture(shape, 128).rgba, t.rgba);
    // The corners are outside the leaf; the blade's middle (or the twig) is inside.
    EXPECT_EQ(t.rgba[3], 0);
    EXPECT_EQ(t.rgba[(128 * 128 - 1) * 4 + 3], 0);
    EXPECT_EQ(t.rgba[(64 * 128 + 64) * 4 + 3], 255);
    EXPECT_EQ(parse_leaf_shape(leaf_shape_name(shape)), shape);
  }
  // Broad blades: darker midrib and veins than the blade around them.
  Image8 t = make_leaf_texture(LeafShape::ovate, 128);
  auto green = [&](int x, int y) { return int(t.rgba[(size_t(y) * 128 + size_t(x)) * 4 + 1]); };
  int midrib = green(64, 60), blade = green(50, 60);
  EXPECT_LT(midrib + 40, blade);
  EXPECT_FALSE(parse_leaf_shape("maple").has_value());
}

TEST(LeafTexture, CardCoversTheTexture) {
  for (LeafShape shape : kLeafShapes) {
    Mesh card = make_leaf_card(shape);
    ASSERT_EQ(card.vertices.size(), 4u);
    ASSERT_EQ(card.indices.size(), 6u);
    float w = leaf_card_aspect(shape);
    EXPECT_GT(w, 0.1f);
    EXPECT_LE(w, 1.0f);
    glm::vec2 uv_lo(1.0f), uv_hi(0.0f);
    for (const Vertex& v : card.vertices) {
      EXPECT_EQ(v.normal, glm::vec3(0, 0, 1));
      EXPECT_EQ(v.position.z, 0.0f);
      EXPECT_NEAR(std::abs(v.position.x), 0.5f * w, 1e-6f);
      // Blade from the origin (v = 1, the texture's bottom row) to the tip (v = 0).
      EXPECT_NEAR(v.uv.y, 1.0f - v.position.y, 1e-6f);
      EXPECT_NEAR(v.uv.x, 0.5f + v.position.x / w, 1e-6f);
      uv_lo = glm::min(uv_lo, v.uv);
      uv_hi = glm::max(uv_hi, v.uv);
    }
    EXPECT_EQ(uv_lo, glm::vec2(0.0f));
    EXPECT_EQ(uv_hi, glm::vec2(1.0f));
    for (size_t i = 0; i < card.indices.size(); i += 3) {
      glm::vec3 a = card.vertices[card.indices[i]].position, b = card.vertices[card.indices[i + 1]].position,
                c = card.vertices[card.indices[i + 2]].position;
      EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f);  // counter-clockwise seen from +Z
    }
  }
}

