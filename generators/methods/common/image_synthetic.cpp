#include "generators/methods/common/image_synthetic.h"

#include <algorithm>
#include <cmath>

#include "generators/core/toml_reader.h"

namespace forest {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Real roots of a t^2 + b t + c = 0 appended to `out` (the linear case when a ~ 0).
void roots(double a, double b, double c, std::vector<double>& out) {
  double scale = std::max({std::abs(a), std::abs(b), std::abs(c), 1e-300});
  if (std::abs(a) < 1e-14 * scale) {
    if (std::abs(b) > 1e-300) out.push_back(-c / b);
    return;
  }
  double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return;
  double s = std::sqrt(disc);
  // Numerically stable pair.
  double q = -0.5 * (b + (b >= 0.0 ? s : -s));
  out.push_back(q / a);
  if (std::abs(q) > 1e-300) out.push_back(c / q);
}

}  // namespace

bool inside(const CrownPrimitive& p, glm::dvec3 x) {
  glm::dvec3 d = x - p.center;
  switch (p.kind) {
    case CrownPrimitive::Kind::Ellipsoid: {
      glm::dvec3 q = d / p.radii;
      return glm::dot(q, q) <= 1.0;
    }
    case CrownPrimitive::Kind::Cylinder:
      return d.y >= 0.0 && d.y <= p.height && d.x * d.x + d.z * d.z <= p.radii.x * p.radii.x;
    case CrownPrimitive::Kind::Cone: {
      if (d.y < 0.0 || d.y > p.height) return false;
      double r = p.radii.x * (1.0 - d.y / p.height);
      return d.x * d.x + d.z * d.z <= r * r;
    }
  }
  return false;
}

bool ray_hits(const CrownPrimitive& p, const Ray& ray, double t0, double t1) {
  std::vector<double> cuts = {t0, t1};
  glm::dvec3 o = ray.origin - p.center, d = ray.direction;
  switch (p.kind) {
    case CrownPrimitive::Kind::Ellipsoid: {
      glm::dvec3 oo = o / p.radii, dd = d / p.radii;
      roots(glm::dot(dd, dd), 2.0 * glm::dot(oo, dd), glm::dot(oo, oo) - 1.0, cuts);
      break;
    }
    case CrownPrimitive::Kind::Cylinder:
    case CrownPrimitive::Kind::Cone: {
      double a = d.x * d.x + d.z * d.z, b = 2.0 * (o.x * d.x + o.z * d.z);
      double c = o.x * o.x + o.z * o.z;
      if (p.kind == CrownPrimitive::Kind::Cylinder) {
        c -= p.radii.x * p.radii.x;
      } else {  // x^2 + z^2 = k^2 (h - y)^2
        double k = p.radii.x / p.height, e = p.height - o.y;
        a -= k * k * d.y * d.y;
        b += 2.0 * k * k * e * d.y;
        c -= k * k * e * e;
      }
      roots(a, b, c, cuts);
      if (std::abs(d.y) > 1e-300) {
        cuts.push_back(-o.y / d.y);
        cuts.push_back((p.height - o.y) / d.y);
      }
      break;
    }
  }
  std::sort(cuts.begin(), cuts.end());
  for (size_t k = 0; k + 1 < cuts.size(); ++k) {
    double a = std::max(cuts[k], t0), b = std::min(cuts[k + 1], t1);
    if (b <= a) continue;
    if (inside(p, ray.origin + ray.direction * (0.5 * (a + b)))) return true;
  }
  return false;
}

CrownSpec read_crown_spec(const TomlTable& t) {
  t.check_keys({"shape", "height", "width", "depth", "trunk_height", "trunk_radius", "branches", "views",
                "resolution", "camera"});
  CrownSpec s;
  s.shape = t.choice("shape", s.shape, {"ellipsoid", "cone", "lobes"});
  s.height = t.number("height", s.height, 0.5, 200.0);
  s.width = t.number("width", s.width, 0.1, 200.0);
  s.depth = t.number("depth", s.width, 0.1, 200.0);
  s.trunk_height = t.number("trunk_height", s.trunk_height, 0.0, 200.0);
  if (s.trunk_height >= 0.9 * s.height) t.fail("trunk_height", "must be below 0.9 * height");
  s.trunk_radius = t.number("trunk_radius", s.trunk_radius, 0.0, 0.25 * s.width);
  s.branches = int(t.integer("branches", s.branches, 0, 32));
  s.views = int(t.integer("views", s.views, 1, 64));
  s.resolution = int(t.integer("resolution", s.resolution, 16, 2048));
  s.perspective = t.choice("camera", "orthographic", {"orthographic", "perspective"}) == "perspective";
  return s;
}

bool inside(const SyntheticTree& tree, glm::dvec3 x) {
  for (const CrownPrimitive& p : tree.parts)
    if (inside(p, x)) return true;
  return false;
}

SyntheticTree make_synthetic_tree(const CrownSpec& s) {
  using K = CrownPrimitive::Kind;
  SyntheticTree tree;
  const double th = s.trunk_height, ch = s.height - th, w = s.width;
  const double dz = s.depth > 0.0 ? s.depth : w;  // z extent of ellipsoid crowns
  double leader_top = th + 0.75 * ch;  // the trunk axis continues into the crown
  if (s.shape == "ellipsoid") {
    tree.parts.push_back({K::Ellipsoid, {0, th + 0.5 * ch, 0}, {0.5 * w, 0.5 * ch, 0.5 * dz}, 0});
  } else if (s.shape == "cone") {
    tree.parts.push_back({K::Cone, {0, th, 0}, {0.5 * w, 0, 0}, ch});
    leader_top = th + 0.85 * ch;
  } else {  // lobes: a top lobe and three side lobes (Shlyakhter 2001's synthetic crown)
    tree.parts.push_back({K::Ellipsoid, {0, th + 0.62 * ch, 0}, {0.25 * w, 0.38 * ch, 0.25 * dz}, 0});
    for (int k = 0; k < 3; ++k) {
      double a = 2.0 * kPi * k / 3.0 + 0.4;
      tree.parts.push_back({K::Ellipsoid, {0.25 * w * std::cos(a), th + 0.35 * ch, 0.25 * dz * std::sin(a)},
                            {0.25 * w, 0.3 * ch, 0.25 * dz}, 0});
    }
  }
  if (s.trunk_radius > 0.0)
    tree.parts.push_back({K::Cylinder, {0, 0, 0}, {s.trunk_radius, 0, 0}, th + 0.3 * ch});

  tree.axes.push_back({{0, 0, 0}, {0, th, 0}, {0, leader_top, 0}});
  for (int k = 0; k < s.branches; ++k) {
    double f = s.branches > 1 ? double(k) / double(s.branches - 1) : 0.5;
    glm::dvec3 start(0, th + ch * (0.12 + 0.5 * f), 0);
    start.y = std::min(start.y, leader_top - 0.05 * ch);
    double az = glm::radians(137.5 * k + 20.0), el = glm::radians(30.0 + 20.0 * f);
    glm::dvec3 dir(std::cos(el) * std::cos(az), std::sin(el), std::cos(el) * std::sin(az));
    // March outward to the crown surface (bounded), end at 85 % of the way.
    double step = s.height / 400.0, len = 0.0;
    for (int i = 0; i < 800 && inside(tree, start + dir * (len + step)); ++i) len += step;
    if (len < 4.0 * step) continue;
    glm::dvec3 end = start + dir * (0.85 * len);
    glm::dvec3 mid = 0.5 * (start + end) + glm::dvec3(0, 0.06 * len, 0);
    if (!inside(tree, mid)) mid = 0.5 * (start + end);
    tree.axes.push_back({start, mid, end});
  }
  double r = 0.55 * std::max(w, dz);
  tree.bounds = {{-r, 0.0, -r}, {r, 1.04 * s.height, r}};
  tree.base = {0, 0, 0};
  return tree;
}

std::vector<Camera> synthetic_cameras(const SyntheticTree& tree, const CrownSpec& s) {
  std::vector<Camera> cams;
  glm::dvec3 c = 0.5 * (tree.bounds.min + tree.bounds.max), size = tree.bounds.size();
  for (int k = 0; k < s.views; ++k) {
    if (!s.perspective) {
      double a = kPi * k / s.views;
      glm::dvec3 dir(-std::sin(a), 0.0, -std::cos(a));
      double extent = 1.08 * std::max(size.y, std::hypot(size.x, size.z));
      cams.push_back(orthographic_camera(s.resolution, s.resolution, c, dir, {0, 1, 0}, extent));
    } else {
      double a = 2.0 * kPi * k / s.views, dist = 2.0 * size.y;
      glm::dvec3 eye(dist * std::sin(a), 0.4 * size.y, dist * std::cos(a));
      double rho = 0.5 * glm::length(size), fov = 2.0 * std::asin(std::min(0.99, rho / glm::length(c - eye)));
      cams.push_back(perspective_camera(s.resolution, s.resolution, eye, c, {0, 1, 0}, 1.05 * glm::degrees(fov)));
    }
  }
  return cams;
}

Mask render_mask(const SyntheticTree& tree, const Camera& camera) {
  Mask m;
  m.width = camera.width;
  m.height = camera.height;
  m.alpha.assign(size_t(m.width) * size_t(m.height), 0.0f);
  m.source = "synthetic";
  for (int j = 0; j < m.height; ++j)
    for (int i = 0; i < m.width; ++i) {
      Ray ray = pixel_ray(camera, {i + 0.5, j + 0.5});
      for (const CrownPrimitive& p : tree.parts)
        if (ray_hits(p, ray, 0.0, 1e5)) {
          m.alpha[size_t(j) * size_t(m.width) + size_t(i)] = 1.0f;
          break;
        }
    }
  return m;
}

ViewSet synthesize_view_set(const CrownSpec& spec) {
  SyntheticTree tree = make_synthetic_tree(spec);
  ViewSet set;
  set.bounds = tree.bounds;
  set.base = tree.base;
  set.source = "synthetic " + spec.shape + " crown";
  for (const Camera& cam : synthetic_cameras(tree, spec)) {
    View v;
    v.camera = cam;
    v.mask = render_mask(tree, cam);
    for (const auto& axis : tree.axes) {
      Polyline2 line;
      for (glm::dvec3 p : axis) line.push_back(project(cam, p).pixel);
      v.attractors.push_back(std::move(line));
    }
    set.views.push_back(std::move(v));
  }
  return set;
}

}  // namespace forest
