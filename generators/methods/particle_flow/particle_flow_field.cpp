#include "generators/methods/particle_flow/particle_flow_field.h"

#include <algorithm>
#include <cmath>

namespace forest {

glm::dvec2 DirectionField2D::at(glm::dvec2 pixel) const {
  // Cell centres sit at (k + 0.5) cells; clamp so the border cells extend outward.
  double x = std::clamp(pixel.x / cell_w - 0.5, 0.0, double(cells - 1));
  double y = std::clamp(pixel.y / cell_h - 0.5, 0.0, double(cells - 1));
  if (!std::isfinite(x) || !std::isfinite(y)) return glm::dvec2(0.0);
  int x0 = std::min(int(x), cells - 1), y0 = std::min(int(y), cells - 1);
  int x1 = std::min(x0 + 1, cells - 1), y1 = std::min(y0 + 1, cells - 1);
  double fx = x - x0, fy = y - y0;
  auto v = [&](int i, int j) { return f[size_t(j) * size_t(cells) + size_t(i)]; };
  return (v(x0, y0) * (1 - fx) + v(x1, y0) * fx) * (1 - fy) + (v(x0, y1) * (1 - fx) + v(x1, y1) * fx) * fy;
}

ClosestPoint closest_on_polylines(const std::vector<Polyline2>& lines, glm::dvec2 x) {
  ClosestPoint best;
  double bd = 1e300;
  for (const Polyline2& line : lines)
    for (size_t k = 1; k < line.size(); ++k) {
      glm::dvec2 a = line[k - 1], b = line[k], ab = b - a;
      double len2 = glm::dot(ab, ab);
      if (len2 < 1e-24) continue;
      double t = std::clamp(glm::dot(x - a, ab) / len2, 0.0, 1.0);
      glm::dvec2 p = a + t * ab;
      double d = glm::length(x - p);
      if (d < bd) {
        bd = d;
        best = {p, -ab / std::sqrt(len2), true};  // toward the root end (the predecessor)
      }
    }
  return best;
}

glm::dvec2 field_value(const std::vector<Polyline2>& lines, glm::dvec2 x, double blend_pixels,
                       const FieldParams& params) {
  ClosestPoint c = closest_on_polylines(lines, x);
  if (!c.found) return glm::dvec2(0.0);
  glm::dvec2 v = c.point - x;
  double d = glm::length(v);
  if (d < 1e-12) return c.tangent;  // on the graph: follow it
  double h = params.constant_h ? params.h_constant : std::min(1.0, d / blend_pixels);
  return h * (v / d) + (1.0 - h) * c.tangent;
}

DirectionField2D build_direction_field(const View& view, const FieldParams& params) {
  DirectionField2D field;
  field.cells = params.cells;
  field.cell_w = double(view.mask.width) / params.cells;
  field.cell_h = double(view.mask.height) / params.cells;
  field.f.resize(size_t(params.cells) * size_t(params.cells));
  double blend = params.blend * std::hypot(double(view.mask.width), double(view.mask.height));
  for (int j = 0; j < params.cells; ++j)
    for (int i = 0; i < params.cells; ++i)
      field.f[size_t(j) * size_t(params.cells) + size_t(i)] =
          field_value(view.attractors, {(i + 0.5) * field.cell_w, (j + 0.5) * field.cell_h}, blend, params);
  return field;
}

DirectionField3D build_direction_field(const ViewSet& set, const FieldParams& params) {
  DirectionField3D out;
  for (const View& v : set.views) {
    if (v.attractors.empty()) continue;
    out.views.push_back(&v);
    out.fields.push_back(build_direction_field(v, params));
  }
  return out;
}

glm::dvec3 DirectionField3D::at(glm::dvec3 world) const {
  glm::dvec3 sum(0.0);
  size_t n = 0;
  for (size_t k = 0; k < views.size(); ++k) {
    Projection p = project(views[k]->camera, world);
    if (!p.in_front()) continue;
    glm::dvec2 f = fields[k].at(p.pixel);
    auto axes = image_axes(views[k]->camera);
    sum += f.x * axes[0] + f.y * axes[1];
    ++n;
  }
  return n ? sum / double(n) : glm::dvec3(0.0);
}

}  // namespace forest
