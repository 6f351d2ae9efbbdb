#include "generators/methods/visual_hull/visual_hull_hull.h"

#include <algorithm>
#include <cmath>

namespace forest {

namespace {

bool in_bounds(const Bounds& b, glm::dvec3 p) {
  return p.x >= b.min.x && p.y >= b.min.y && p.z >= b.min.z && p.x <= b.max.x && p.y <= b.max.y &&
         p.z <= b.max.z;
}

bool on_silhouette(const View& v, glm::dvec3 p) {
  Projection pr = project(v.camera, p);
  if (!pr.in_front()) return false;
  if (!(pr.pixel.x >= 0.0 && pr.pixel.y >= 0.0)) return false;  // also rejects NaN
  return v.mask.inside(int(std::floor(pr.pixel.x)), int(std::floor(pr.pixel.y)));
}

// Clips [t0, t1] to the bounds box (slab method); false when the ray misses it.
bool clip_to_bounds(const Bounds& b, glm::dvec3 o, glm::dvec3 d, double& t0, double& t1) {
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-300) {
      if (o[k] < b.min[k] || o[k] > b.max[k]) return false;
      continue;
    }
    double ta = (b.min[k] - o[k]) / d[k], tb = (b.max[k] - o[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t1 > t0;
}

// Intervals of [t0, t1] where the ray lies on a silhouette pixel of view v.
void view_intervals(const View& v, glm::dvec3 o, glm::dvec3 d, double t0, double t1,
                    std::vector<Interval>& out) {
  out.clear();
  const glm::dvec4 c0 = v.camera.view_proj * glm::dvec4(o, 1.0);
  const glm::dvec4 c1 = v.camera.view_proj * glm::dvec4(d, 0.0);
  double a = t0, b = t1;
  if (std::abs(c1.w) > 1e-300) {  // keep w > 0 (in front of a perspective camera)
    double tw = -c0.w / c1.w;
    if (c1.w > 0.0) a = std::max(a, tw);
    else b = std::min(b, tw);
  } else if (c0.w <= 0.0) {
    return;
  }
  if (!(b > a)) return;
  std::vector<double> cuts = {a, b};
  const double ea = a + 1e-9 * (b - a), eb = b - 1e-9 * (b - a);
  // Pixel coordinate along image axis `axis` (0: u, 1: v) at parameter t.
  auto coord = [&](int axis, double t) {
    glm::dvec4 c = c0 + t * c1;
    double s = (axis == 0 ? c.x : c.y) / c.w;
    int n = axis == 0 ? v.camera.width : v.camera.height;
    return axis == 0 ? (s + 1.0) * 0.5 * n : (1.0 - s) * 0.5 * n;
  };
  for (int axis = 0; axis < 2; ++axis) {
    const int n = axis == 0 ? v.camera.width : v.camera.height;
    double ua = coord(axis, ea), ub = coord(axis, eb);
    if (!std::isfinite(ua) || !std::isfinite(ub)) continue;
    int lo = int(std::clamp(std::floor(std::min(ua, ub)), 0.0, double(n)));
    int hi = int(std::clamp(std::ceil(std::max(ua, ub)), 0.0, double(n)));
    for (int i = lo; i <= hi; ++i) {
      // Grid line i in NDC, then C.axis - s C.w = 0 is linear in t.
      double s = axis == 0 ? 2.0 * i / n - 1.0 : 1.0 - 2.0 * i / n;
      double num = (axis == 0 ? c0.x : c0.y) - s * c0.w;
      double den = (axis == 0 ? c1.x : c1.y) - s * c1.w;
      if (std::abs(den) < 1e-300) continue;
      double t = -num / den;
      if (t > a && t < b) cuts.push_back(t);
    }
  }
  std::sort(cuts.begin(), cuts.end());
  for (size_t k = 0; k + 1 < cuts.size(); ++k) {
    double ta = cuts[k], tb = cuts[k + 1];
    if (!(tb > ta)) continue;
    if (!on_silhouette(v, o + d * (0.5 * (ta + tb)))) continue;
    if (!out.empty() && out.back().b >= ta) out.back().b = tb;
    else out.push_back({ta, tb});
  }
}

std::vector<Interval> intersect(const std::vector<Interval>& x, const std::vector<Interval>& y) {
  std::vector<Interval> out;
  size_t i = 0, j = 0;
  while (i < x.size() && j < y.size()) {
    double a = std::max(x[i].a, y[j].a), b = std::min(x[i].b, y[j].b);
    if (b > a) out.push_back({a, b});
    (x[i].b < y[j].b) ? ++i : ++j;
  }
  return out;
}

}  // namespace

bool inside_hull(const ViewSet& set, glm::dvec3 p) {
  if (!in_bounds(set.bounds, p)) return false;
  for (const View& v : set.views)
    if (!on_silhouette(v, p)) return false;
  return true;
}

std::vector<Interval> hull_intervals(const ViewSet& set, glm::dvec3 o, glm::dvec3 d, double t0,
                                     double t1, int skip_view) {
  if (!clip_to_bounds(set.bounds, o, d, t0, t1)) return {};
  std::vector<Interval> current = {{t0, t1}}, view;
  for (size_t k = 0; k < set.views.size(); ++k) {
    if (int(k) == skip_view) continue;
    view_intervals(set.views[k], o, d, current.front().a, current.back().b, view);
    current = intersect(current, view);
    if (current.empty()) break;
  }
  return current;
}

double inside_fraction(const ViewSet& set, glm::dvec3 p, glm::dvec3 q) {
  if (!inside_hull(set, p)) return 0.0;
  auto iv = hull_intervals(set, p, q - p, 0.0, 1.0);
  if (iv.empty() || iv.front().a > 1e-9) return 0.0;
  return std::min(1.0, iv.front().b);
}

bool segment_inside_hull(const ViewSet& set, glm::dvec3 p, glm::dvec3 q) {
  return inside_fraction(set, p, q) >= 1.0 - 1e-12 && inside_hull(set, q);
}

double hull_volume(const ViewSet& set, int columns) {
  const Bounds& b = set.bounds;
  glm::dvec3 size = b.size();
  double dx = size.x / columns, dz = size.z / columns, volume = 0.0;
  for (int k = 0; k < columns; ++k)
    for (int i = 0; i < columns; ++i) {
      glm::dvec3 o(b.min.x + (i + 0.5) * dx, b.min.y - 1.0, b.min.z + (k + 0.5) * dz);
      for (const Interval& iv : hull_intervals(set, o, {0, 1, 0}, 0.0, size.y + 2.0)) volume += (iv.b - iv.a) * dx * dz;
    }
  return volume;
}

double reprojection_iou(const ViewSet& set, size_t v) {
  const View& view = set.views[v];
  size_t mask = 0, covered = 0;
  for (int j = 0; j < view.mask.height; ++j)
    for (int i = 0; i < view.mask.width; ++i) {
      // Outside the mask the pixel's centre ray never meets cone v, so never the hull.
      if (!view.mask.inside(i, j)) continue;
      ++mask;
      Ray r = pixel_ray(view.camera, {i + 0.5, j + 0.5});
      if (!hull_intervals(set, r.origin, r.direction, 0.0, 1e7, int(v)).empty()) ++covered;
    }
  return mask ? double(covered) / double(mask) : 0.0;
}

VoxelGrid voxelize_hull(const ViewSet& set, int n) {
  VoxelGrid g;
  glm::dvec3 size = set.bounds.size();
  g.cell = std::max({size.x, size.y, size.z}) / n;
  g.dims = glm::max(glm::ivec3(glm::ceil(size / g.cell)), glm::ivec3(1));
  g.origin = set.bounds.min;
  g.occupied.assign(size_t(g.dims.x) * size_t(g.dims.y) * size_t(g.dims.z), 0);
  for (int z = 0; z < g.dims.z; ++z)
    for (int y = 0; y < g.dims.y; ++y)
      for (int x = 0; x < g.dims.x; ++x) g.occupied[g.index(x, y, z)] = inside_hull(set, g.center(x, y, z));
  return g;
}

}  // namespace forest
