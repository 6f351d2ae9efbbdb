// Small frame helpers shared by the mesher and leaf placement.
#pragma once
#include <cmath>

#include <glm/glm.hpp>

namespace forest {

// A unit vector perpendicular to unit `a`, chosen deterministically (seeds a frame).
inline glm::vec3 any_perpendicular(glm::vec3 a) {
  glm::vec3 helper = std::abs(a.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::normalize(glm::cross(a, helper));
}

}  // namespace forest
