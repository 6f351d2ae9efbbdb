// The 3D convex hull of a point set (quickhull, Barber et al. 1996), for measuring how deep
// leaves sit inside their crown (crown_depth.h). Robust by construction: the points are
// snapped to an integer grid (2^20 steps over their box's longest side) and every decision
// is an exact integer determinant, so coplanar, collinear and repeated points (cube faces,
// leaves along a straight shoot, leaves sharing a twig tip) cannot fold the hull. The hull
// is exactly that of the snapped points, each within half a grid step per axis of its input.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace forest {

struct HullPlane {
  glm::dvec3 normal{0.0};  // unit, outward
  double offset = 0.0;     // dot(normal, x) <= offset inside
};

struct ConvexHull {
  std::vector<glm::uvec3> triangles;  // indices into the input points, counter-clockwise from outside
  std::vector<HullPlane> planes;      // one per triangle
  // The grid step (m): distances to the planes are exact for the snapped points, within
  // √3/2 of it for the input points. A point set without volume on this grid has no triangles.
  double tolerance = 0.0;
  bool solid() const { return !triangles.empty(); }
};

// Empty (no triangles) when fewer than four points span a volume on the grid.
ConvexHull convex_hull(std::span<const glm::vec3> points);

// Distance from `p` to the hull's surface when p is inside (the smallest gap to a face
// plane, which for a convex polytope is the distance to its boundary); 0 for a point on or
// outside it, and for a hull without volume.
double depth_below_hull(const ConvexHull& hull, glm::dvec3 p);

}  // namespace forest
