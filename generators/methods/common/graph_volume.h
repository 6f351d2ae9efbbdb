// Crown and trunk primitives of the least-cost-path methods (Xu 2015 ch4.4.1 and ch5.3.2):
// the volumes that graph nodes and endpoints are sampled in. A volume is a union of shapes.
#pragma once
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace forest {

class TomlTable;

enum class ShapeKind {
  Sphere,         // center, radius
  SpherePortion,  // "portion of sphere with α": |p − c| ≤ radius and ∠(p − c, axis) ≤ angle
  Ellipsoid,      // center, radii
  HalfEllipsoid,  // ellipsoid above the plane through center normal to +Y (ch5.3.2 crowns)
  Cylinder,       // base center, axis (may be tilted), radius, height
  Cone,           // base center, axis, base radius, height (apex at center + axis·height)
};

struct Shape {
  ShapeKind kind = ShapeKind::Sphere;
  glm::vec3 center{0.0f};
  glm::vec3 axis{0.0f, 1.0f, 0.0f};  // unit
  glm::vec3 radii{1.0f};
  float radius = 1.0f;
  float height = 1.0f;
  float angle = 3.14159265f;  // radians, SpherePortion only
  bool endpoints = true;      // may hold endpoints (a trunk cylinder usually may not)
};

struct Box {
  glm::vec3 lo{0.0f}, hi{0.0f};
};

bool shape_contains(const Shape& s, glm::vec3 p);
Box shape_bounds(const Shape& s);

bool volume_contains(std::span<const Shape> shapes, glm::vec3 p);
Box volume_bounds(std::span<const Shape> shapes);

// p lies inside the union but within `thickness` of its surface: one of 26 probes at that
// distance (axes, face and space diagonals) leaves the union. The thesis' endpoint shell d_e.
bool in_surface_shell(std::span<const Shape> shapes, glm::vec3 p, float thickness);

// One [[volume]] table: shape = "sphere" | "sphere_portion" | "hemisphere" | "ellipsoid" |
// "half_ellipsoid" | "cylinder" | "cone", center, axis, radius, radii, height, angle (deg),
// endpoints (bool). Lengths in meters. Errors name file, line and key.
Shape read_shape(const TomlTable& t);

}  // namespace forest
