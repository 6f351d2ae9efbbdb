// Joining branch cross-sections at a fork (Neubert 2012 ch5: "cut all branches back by the
// largest pairwise r_sphere; join cross-sections").
//
// The rings of all branches at a fork (the incoming branch, its continuation and the side
// branches), each cut where its axis leaves a sphere around the fork, are projected radially
// onto the unit sphere around the fork center. A ring that is a circle centered on a ray from
// the center and perpendicular to it projects to a small circle of the sphere, the boundary
// of a spherical cap; when the caps are pairwise disjoint, the convex hull of all projected
// points (every one of them is extreme: they all lie on the sphere) contains each ring as a
// face, so the hull minus those faces is a sphere with one hole per ring whose boundary edges
// are exactly the ring edges. Mapped back to the unprojected ring vertices that triangulation
// closes the fork: no holes, no extra vertices, and it never self-intersects because it is a
// radial graph over the sphere. To keep the hull non-degenerate, each cap gets an extra point
// on its axis just above the ring's plane (the ring points are exactly co-circular);
// triangles touching such a pole are the caps and are dropped.
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace forest {

struct JunctionRing {
  std::vector<glm::vec3> points;  // ring vertices in order, at least 3
  glm::vec3 axis{0.0f, 1.0f, 0.0f};  // unit: from the fork center toward the ring's center
};

// A junction triangle corner: vertex `index` of ring `ring`.
struct RingVertex {
  uint32_t ring = 0;
  uint32_t index = 0;
  bool operator==(const RingVertex&) const = default;
};

// Triangles (counter-clockwise seen from outside the fork) whose boundary is exactly the
// rings' edges, each used once, in the direction opposite to the one a tube leaving the fork
// through that ring (or arriving at it) uses. Returns false, and no triangles, when the rings
// cannot be joined this way: overlapping caps, fewer than 2 rings, degenerate input, or a
// hull that fails the check.
bool join_rings(glm::vec3 center, std::span<const JunctionRing> rings,
                std::vector<std::array<RingVertex, 3>>* triangles);

// Convex hull of points (double precision, incremental): outward triangles indexing `points`.
// Points within a tiny distance of the hull may be left out. False when all points are
// (nearly) coplanar.
bool convex_hull(std::span<const glm::dvec3> points, std::vector<std::array<uint32_t, 3>>* faces);

}  // namespace forest
