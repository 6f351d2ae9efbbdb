// The leaf card as the renderer draws it (engine/render/leaf_card.h): one triangle around the
// card's quad whose uv extends the quad's, so that the fragment shaders' unit-square test cuts
// it back to exactly the quad.
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include "engine/render/leaf_card.h"
#include "generators/mesh/foliage_card.h"

using namespace forest;

namespace {

float cross2(glm::vec2 a, glm::vec2 b) { return a.x * b.y - a.y * b.x; }

// Barycentric coordinates of p in the triangle of the xy of t.
glm::vec3 barycentric(const glm::vec4 t[3], glm::vec2 p) {
  glm::vec2 a(t[0]), b(t[1]), c(t[2]);
  float area = cross2(b - a, c - a);
  return glm::vec3(cross2(b - p, c - p), cross2(c - p, a - p), cross2(a - p, b - p)) / area;
}

Mesh shoot_card(bool single_leaf) {
  ShootDesign d;
  d.single_leaf = single_leaf;
  return make_foliage_card(d);
}

}  // namespace

TEST(LeafCard, TriangleHoldsTheQuadAndCarriesItsUv) {
  for (bool single : {true, false}) {
    glm::vec4 q[4], t[3];
    ASSERT_TRUE(card_quad_corners(shoot_card(single), q)) << single;
    leaf_triangle(q, t);
    // Wound as the quad, twice its area (the least a triangle around a parallelogram can have).
    float quad_area = cross2(glm::vec2(q[1] - q[0]), glm::vec2(q[3] - q[0]));
    float tri_area = 0.5f * cross2(glm::vec2(t[1] - t[0]), glm::vec2(t[2] - t[0]));
    ASSERT_GT(quad_area, 0.0f);
    EXPECT_NEAR(tri_area, 2.0f * quad_area, 1e-5f * quad_area);
    for (int k = 0; k < 4; ++k) {
      glm::vec3 w = barycentric(t, glm::vec2(q[k]));
      EXPECT_GE(std::min({w.x, w.y, w.z}), -1e-5f) << "quad corner " << k << " outside the triangle";
      // The triangle's uv at the quad's corner is the quad's uv there.
      glm::vec2 uv = w.x * glm::vec2(t[0].z, t[0].w) + w.y * glm::vec2(t[1].z, t[1].w) + w.z * glm::vec2(t[2].z, t[2].w);
      EXPECT_NEAR(uv.x, q[k].z, 1e-5f) << k;
      EXPECT_NEAR(uv.y, q[k].w, 1e-5f) << k;
    }
    // Points of the triangle outside the quad have uv outside the unit square (the shaders'
    // cut), points inside the quad inside it.
    for (float a = 0.02f; a < 1.0f; a += 0.07f)
      for (float b = 0.02f; a + b < 1.0f; b += 0.07f) {
        glm::vec4 p = t[0] + a * (t[1] - t[0]) + b * (t[2] - t[0]);
        glm::vec2 rel(p - q[0]);
        float s = cross2(rel, glm::vec2(q[3] - q[0])) / quad_area, r = cross2(glm::vec2(q[1] - q[0]), rel) / quad_area;
        bool in_quad = s >= 0.0f && s <= 1.0f && r >= 0.0f && r <= 1.0f;
        bool in_square = p.z >= 0.0f && p.z <= 1.0f && p.w >= 0.0f && p.w <= 1.0f;
        EXPECT_EQ(in_quad, in_square) << a << " " << b;
      }
  }
}

TEST(LeafCard, OnlyAffineQuadsBecomeTriangles) {
  Mesh card = shoot_card(true);
  glm::vec4 q[4];
  ASSERT_TRUE(card_quad_corners(card, q));
  Mesh bent = card;
  bent.vertices[2].uv.x += 0.3f;  // uv no longer one affine map of the card's plane
  EXPECT_FALSE(card_quad_corners(bent, q));
  Mesh lifted = card;
  lifted.vertices[1].position.z = 0.1f;
  EXPECT_FALSE(card_quad_corners(lifted, q));
  Mesh three = card;
  three.vertices.pop_back();
  three.indices = {0, 1, 2};
  EXPECT_FALSE(card_quad_corners(three, q));
}
