// Method `silhouettes` (Wither 2009, Wither et al. 2009), part 1: 2D geometry of silhouettes
// and their bumps. A bump is a terminal of the silhouette's geometric skeleton (step A).
// The terminals of the medial axis are the centres of curvature at the outline's curvature
// maxima (Blum 1967), so we find them directly on the outline: E = boundary point at a
// curvature maximum moved inward by the radius of curvature, T_E = the outward normal there.
// [ours: the paper uses a chordal-axis skeleton; a Zhang-Suen image skeleton we tried first
// lost mild bumps whose necks are wide.] Only convex runs whose curvature exceeds
// `significance` times that of the circle of equal perimeter make a bump (a circle or a
// smooth ellipse has none: the fill-in covers such crowns).
#pragma once
#include <vector>

#include <glm/glm.hpp>

namespace forest {

using Polygon2 = std::vector<glm::dvec2>;  // closed implicitly (last joins first)

bool point_in_polygon(const Polygon2& polygon, glm::dvec2 p);
double polygon_area(const Polygon2& polygon);  // absolute
// Fraction of `crown`'s area inside the union of `others`, by sampling a grid of
// resolution x resolution cells over crown's bounding box (cell centres).
double crown_overlap(const Polygon2& crown, const std::vector<Polygon2>& others, int resolution = 48);

// An open polyline with arc-length parameter t in [0, 1].
struct Polyline2 {
  std::vector<glm::dvec2> points;
  std::vector<double> cumulative;  // arc length at each point
  explicit Polyline2(std::vector<glm::dvec2> pts);
  double length() const { return cumulative.empty() ? 0.0 : cumulative.back(); }
  glm::dvec2 at(double t) const;
  glm::dvec2 tangent(double t) const;  // unit
  double closest_t(glm::dvec2 p) const;
};

// Cubic Hermite curve P(s), s in [0, 1], P(0) = p0, P(1) = p1, P'(0) = m0, P'(1) = m1.
glm::dvec2 hermite(glm::dvec2 p0, glm::dvec2 m0, glm::dvec2 p1, glm::dvec2 m1, double s);
glm::dvec2 hermite_derivative(glm::dvec2 p0, glm::dvec2 m0, glm::dvec2 p1, glm::dvec2 m1, double s);
std::vector<glm::dvec2> hermite_polyline(glm::dvec2 p0, glm::dvec2 m0, glm::dvec2 p1, glm::dvec2 m1, int segments);

struct Bump {
  glm::dvec2 end{0.0};      // E: the skeleton terminal
  glm::dvec2 tangent{0.0};  // T_E: unit, pointing out of the skeleton at E
  double radius = 0.0;      // inscribed radius at E (distance to the silhouette)
};

struct SkeletonParams {
  int samples = 256;          // outline samples
  int window = 3;             // curvature from headings +-window samples apart
  double significance = 2.0;  // curvature threshold, in units of 2 pi / perimeter
};

// Bumps of a closed silhouette, ordered by angle around the silhouette's centroid
// (counter-clockwise from +x). Empty for a degenerate polygon.
std::vector<Bump> silhouette_bumps(const Polygon2& silhouette, const SkeletonParams& params = {});

}  // namespace forest
