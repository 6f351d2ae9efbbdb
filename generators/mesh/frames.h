// Frames along curves, shared by the mesher and leaf placement. Frenet frames fail on
// straight parts (no normal) and flip at inflections; tubes and leaves use rotation-minimizing
// frames by parallel transport instead (Neubert 2012 ch5, Hanson 1995).
#pragma once
#include <cmath>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace forest {

// A unit vector perpendicular to unit `a`, chosen deterministically (seeds a frame).
inline glm::vec3 any_perpendicular(glm::vec3 a) {
  glm::vec3 helper = std::abs(a.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::normalize(glm::cross(a, helper));
}

// Rodrigues rotation of v about the unit axis k by `angle` radians.
inline glm::vec3 rotate_about(glm::vec3 v, glm::vec3 k, float angle) {
  float c = std::cos(angle), s = std::sin(angle);
  return v * c + glm::cross(k, v) * s + k * glm::dot(k, v) * (1.0f - c);
}

// An orthonormal, right-handed frame: binormal = tangent × normal (so normal × binormal =
// tangent). A tube ring point at angle θ is center + r (cos θ normal + sin θ binormal).
struct Frame {
  glm::vec3 tangent{0.0f, 1.0f, 0.0f};
  glm::vec3 normal{1.0f, 0.0f, 0.0f};
  glm::vec3 binormal{0.0f, 0.0f, -1.0f};
};

// The minimal rotation that takes unit `from` to unit `to` (about from × to by
// arccos(from · to)) applied to v; the identity when the two are parallel. For opposite
// vectors the axis is any perpendicular of `from`.
glm::vec3 transport(glm::vec3 v, glm::vec3 from, glm::vec3 to);

// Parallel transport (Hanson 1995) along unit tangents: the first frame's normal is
// `normal0` made perpendicular to tangents[0] (any_perpendicular when it is parallel or zero);
// each next normal is the previous one rotated by the minimal rotation from T_i to T_{i+1},
// then re-orthogonalized against rounding. No twist about the tangent, no flips at
// inflections, constant frames on straight parts.
std::vector<Frame> parallel_transport(std::span<const glm::vec3> tangents,
                                      glm::vec3 normal0 = glm::vec3(0.0f));

// Same over a polyline: the tangent at an inner point is the normalized sum of its two unit
// segment directions, at the ends the end segment's direction. Coincident consecutive points
// reuse the previous tangent. Fewer than two distinct points: frames along +Y.
std::vector<Frame> parallel_transport_polyline(std::span<const glm::vec3> points,
                                               glm::vec3 normal0 = glm::vec3(0.0f));

}  // namespace forest
