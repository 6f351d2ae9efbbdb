// Direction fields from attractor polylines (Neubert 2012 ch3.5, eq. 3.7).
// Per image, a grid of cells (100 x 100 by default) over the image; at each cell centre x:
// g = closest point of the attractor graph, v = g - x, d = |v|, t = the graph's tangent at g
// pointing toward the root, f = h(d) v/|v| + (1 - h(d)) t/|t|. h is linear,
// h(d) = min(1, d / blend), or constant (a fixed approach angle). Since f is a convex
// combination of unit vectors, |f| <= 1; bilinear lookup and averaging over views keep it so.
// In 3D a particle is projected into every image with attractors, the 2D vectors are lifted
// along the image axes (image_axes) and averaged.
#pragma once
#include <vector>

#include "generators/methods/common/image_inputs.h"

namespace forest {

struct FieldParams {
  int cells = 100;           // grid cells per image side
  bool constant_h = false;   // h(d) = h_constant instead of linear
  double h_constant = 0.5;
  double blend = 0.08;       // linear h reaches 1 at this fraction of the image diagonal
};

struct DirectionField2D {
  int cells = 0;
  double cell_w = 1.0, cell_h = 1.0;  // pixels per cell
  std::vector<glm::dvec2> f;          // cells x cells, row-major, image axes (u right, v down)
  glm::dvec2 at(glm::dvec2 pixel) const;  // bilinear, clamped at the border
};

// Closest point of the polylines to x and the unit tangent there pointing toward the root
// (from a point toward its predecessor). Polylines with < 2 points are ignored.
struct ClosestPoint {
  glm::dvec2 point{0.0};
  glm::dvec2 tangent{0.0};
  bool found = false;
};
ClosestPoint closest_on_polylines(const std::vector<Polyline2>& lines, glm::dvec2 x);

// Eq. 3.7 at one point.
glm::dvec2 field_value(const std::vector<Polyline2>& lines, glm::dvec2 x, double blend_pixels,
                       const FieldParams& params);

DirectionField2D build_direction_field(const View& view, const FieldParams& params);

// 3D field of a view set: average of the lifted 2D fields of the views that have attractors.
struct DirectionField3D {
  std::vector<const View*> views;
  std::vector<DirectionField2D> fields;
  bool empty() const { return views.empty(); }
  glm::dvec3 at(glm::dvec3 world) const;
};
DirectionField3D build_direction_field(const ViewSet& set, const FieldParams& params);

}  // namespace forest
