#include "generators/methods/common/graph_volume.h"

#include <algorithm>
#include <cmath>

#include "generators/core/toml_reader.h"

namespace forest {

namespace {
constexpr float kPi = 3.14159265358979323846f;

Box box_of_disc_sweep(glm::vec3 base, glm::vec3 axis, float radius, float height) {
  // Extent of a disc of `radius` normal to axis: radius * sqrt(1 - axis_i^2) per component.
  glm::vec3 e(radius * std::sqrt(std::max(0.0f, 1.0f - axis.x * axis.x)),
              radius * std::sqrt(std::max(0.0f, 1.0f - axis.y * axis.y)),
              radius * std::sqrt(std::max(0.0f, 1.0f - axis.z * axis.z)));
  glm::vec3 top = base + axis * height;
  return {glm::min(base, top) - e, glm::max(base, top) + e};
}
}  // namespace

bool shape_contains(const Shape& s, glm::vec3 p) {
  glm::vec3 q = p - s.center;
  switch (s.kind) {
    case ShapeKind::Sphere:
      return glm::dot(q, q) <= s.radius * s.radius;
    case ShapeKind::SpherePortion: {
      float len = glm::length(q);
      if (len > s.radius) return false;
      if (len == 0.0f) return true;  // the apex itself
      return glm::dot(q, s.axis) >= len * std::cos(s.angle);
    }
    case ShapeKind::Ellipsoid:
    case ShapeKind::HalfEllipsoid: {
      if (s.kind == ShapeKind::HalfEllipsoid && q.y < 0.0f) return false;
      glm::vec3 n = q / s.radii;
      return glm::dot(n, n) <= 1.0f;
    }
    case ShapeKind::Cylinder: {
      float h = glm::dot(q, s.axis);
      if (h < 0.0f || h > s.height) return false;
      glm::vec3 radial = q - h * s.axis;
      return glm::dot(radial, radial) <= s.radius * s.radius;
    }
    case ShapeKind::Cone: {
      float h = glm::dot(q, s.axis);
      if (h < 0.0f || h > s.height) return false;
      float r = s.radius * (1.0f - h / s.height);
      glm::vec3 radial = q - h * s.axis;
      return glm::dot(radial, radial) <= r * r;
    }
  }
  return false;
}

Box shape_bounds(const Shape& s) {
  switch (s.kind) {
    case ShapeKind::Sphere:
    case ShapeKind::SpherePortion:  // conservative: the whole sphere
      return {s.center - glm::vec3(s.radius), s.center + glm::vec3(s.radius)};
    case ShapeKind::Ellipsoid:
      return {s.center - s.radii, s.center + s.radii};
    case ShapeKind::HalfEllipsoid:
      return {s.center - glm::vec3(s.radii.x, 0.0f, s.radii.z), s.center + s.radii};
    case ShapeKind::Cylinder:
    case ShapeKind::Cone:
      return box_of_disc_sweep(s.center, s.axis, s.radius, s.height);
  }
  return {};
}

bool volume_contains(std::span<const Shape> shapes, glm::vec3 p) {
  for (const Shape& s : shapes)
    if (shape_contains(s, p)) return true;
  return false;
}

Box volume_bounds(std::span<const Shape> shapes) {
  Box b{glm::vec3(1e30f), glm::vec3(-1e30f)};
  for (const Shape& s : shapes) {
    Box sb = shape_bounds(s);
    b.lo = glm::min(b.lo, sb.lo);
    b.hi = glm::max(b.hi, sb.hi);
  }
  if (shapes.empty()) b = {};
  return b;
}

bool in_surface_shell(std::span<const Shape> shapes, glm::vec3 p, float thickness) {
  if (!volume_contains(shapes, p)) return false;
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz) {
        if (dx == 0 && dy == 0 && dz == 0) continue;
        glm::vec3 dir = glm::normalize(glm::vec3(float(dx), float(dy), float(dz)));
        if (!volume_contains(shapes, p + thickness * dir)) return true;
      }
  return false;
}

Shape read_shape(const TomlTable& t) {
  t.check_keys({"shape", "center", "axis", "radius", "radii", "height", "angle", "endpoints"});
  Shape s;
  std::string kind = t.choice("shape", "sphere",
                              {"sphere", "sphere_portion", "hemisphere", "ellipsoid",
                               "half_ellipsoid", "cylinder", "cone"});
  s.center = t.vec3("center", glm::vec3(0.0f), -1000.0, 1000.0);
  glm::vec3 axis = t.vec3("axis", glm::vec3(0, 1, 0), -1.0, 1.0);
  if (glm::length(axis) < 1e-3f) t.fail("axis", "must not be the zero vector");
  s.axis = glm::normalize(axis);
  s.radius = float(t.number("radius", 1.0, 1e-3, 1000.0));
  s.radii = t.vec3("radii", glm::vec3(s.radius), 1e-3, 1000.0);
  s.height = float(t.number("height", 1.0, 1e-3, 1000.0));
  s.angle = float(t.number("angle", 180.0, 1.0, 180.0)) * kPi / 180.0f;
  if (kind == "sphere") {
    s.kind = ShapeKind::Sphere;
  } else if (kind == "sphere_portion") {
    s.kind = ShapeKind::SpherePortion;
  } else if (kind == "hemisphere") {
    s.kind = ShapeKind::SpherePortion;
    if (t.has("angle")) t.fail("angle", "a hemisphere's angle is 90 degrees; use sphere_portion");
    s.angle = 0.5f * kPi;
  } else if (kind == "ellipsoid") {
    s.kind = ShapeKind::Ellipsoid;
  } else if (kind == "half_ellipsoid") {
    s.kind = ShapeKind::HalfEllipsoid;
  } else if (kind == "cylinder") {
    s.kind = ShapeKind::Cylinder;
  } else {
    s.kind = ShapeKind::Cone;
  }
  // A trunk cylinder holds paths, not endpoints, unless asked.
  s.endpoints = t.boolean("endpoints", s.kind != ShapeKind::Cylinder);
  return s;
}

}  // namespace forest
