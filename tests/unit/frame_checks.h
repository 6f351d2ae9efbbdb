// Checks of coordinate frames in the unit tests.
#pragma once
#include <gtest/gtest.h>

#include <glm/glm.hpp>

namespace forest::test {

// x, y, z are unit vectors, pairwise perpendicular, and right-handed: z = x × y (within 1e-5).
inline void expect_right_handed_orthonormal(glm::vec3 x, glm::vec3 y, glm::vec3 z) {
  EXPECT_NEAR(glm::length(x), 1.0f, 1e-5f);
  EXPECT_NEAR(glm::length(y), 1.0f, 1e-5f);
  EXPECT_NEAR(glm::length(z), 1.0f, 1e-5f);
  EXPECT_NEAR(glm::dot(x, y), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::dot(x, z), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::dot(y, z), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(glm::cross(x, y) - z), 0.0f, 1e-5f);
}

}  // namespace forest::test
