#include "generators/methods/silhouettes/silhouettes_skeleton.h"

#include <algorithm>
#include <cmath>

namespace forest {

bool point_in_polygon(const Polygon2& poly, glm::dvec2 p) {
  bool inside = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    glm::dvec2 a = poly[i], b = poly[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) inside = !inside;
  }
  return inside;
}

double polygon_area(const Polygon2& poly) {
  double a = 0.0;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) a += poly[j].x * poly[i].y - poly[i].x * poly[j].y;
  return 0.5 * std::abs(a);
}

double crown_overlap(const Polygon2& crown, const std::vector<Polygon2>& others, int res) {
  if (crown.size() < 3) return 0.0;
  glm::dvec2 lo(1e300), hi(-1e300);
  for (glm::dvec2 p : crown) lo = glm::min(lo, p), hi = glm::max(hi, p);
  size_t in = 0, shared = 0;
  for (int j = 0; j < res; ++j)
    for (int i = 0; i < res; ++i) {
      glm::dvec2 p = lo + (hi - lo) * glm::dvec2((i + 0.5) / res, (j + 0.5) / res);
      if (!point_in_polygon(crown, p)) continue;
      ++in;
      for (const Polygon2& o : others)
        if (o.size() >= 3 && point_in_polygon(o, p)) {
          ++shared;
          break;
        }
    }
  return in ? double(shared) / double(in) : 0.0;
}

Polyline2::Polyline2(std::vector<glm::dvec2> pts) : points(std::move(pts)) {
  double s = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    if (i) s += glm::length(points[i] - points[i - 1]);
    cumulative.push_back(s);
  }
}

glm::dvec2 Polyline2::at(double t) const {
  if (points.size() < 2) return points.empty() ? glm::dvec2(0.0) : points[0];
  double s = std::clamp(t, 0.0, 1.0) * length();
  size_t k = size_t(std::upper_bound(cumulative.begin(), cumulative.end(), s) - cumulative.begin());
  k = std::clamp<size_t>(k, 1, points.size() - 1);
  double seg = cumulative[k] - cumulative[k - 1];
  double a = seg > 0 ? (s - cumulative[k - 1]) / seg : 0.0;
  return glm::mix(points[k - 1], points[k], a);
}

glm::dvec2 Polyline2::tangent(double t) const {
  if (points.size() < 2) return {0, 1};
  double s = std::clamp(t, 0.0, 1.0) * length();
  size_t k = size_t(std::upper_bound(cumulative.begin(), cumulative.end(), s) - cumulative.begin());
  k = std::clamp<size_t>(k, 1, points.size() - 1);
  glm::dvec2 d = points[k] - points[k - 1];
  return glm::length(d) > 0 ? glm::normalize(d) : glm::dvec2(0, 1);
}

double Polyline2::closest_t(glm::dvec2 p) const {
  double best = 1e300, best_s = 0.0;
  for (size_t k = 1; k < points.size(); ++k) {
    glm::dvec2 a = points[k - 1], ab = points[k] - a;
    double l2 = glm::dot(ab, ab);
    double u = l2 > 0 ? std::clamp(glm::dot(p - a, ab) / l2, 0.0, 1.0) : 0.0;
    double d = glm::length(a + u * ab - p);
    if (d < best) best = d, best_s = cumulative[k - 1] + u * std::sqrt(l2);
  }
  return length() > 0 ? best_s / length() : 0.0;
}

glm::dvec2 hermite(glm::dvec2 p0, glm::dvec2 m0, glm::dvec2 p1, glm::dvec2 m1, double s) {
  double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * m1;
}

glm::dvec2 hermite_derivative(glm::dvec2 p0, glm::dvec2 m0, glm::dvec2 p1, glm::dvec2 m1, double s) {
  double s2 = s * s;
  return (6 * s2 - 6 * s) * p0 + (3 * s2 - 4 * s + 1) * m0 + (-6 * s2 + 6 * s) * p1 + (3 * s2 - 2 * s) * m1;
}

std::vector<glm::dvec2> hermite_polyline(glm::dvec2 p0, glm::dvec2 m0, glm::dvec2 p1, glm::dvec2 m1, int n) {
  std::vector<glm::dvec2> out;
  for (int k = 0; k <= n; ++k) out.push_back(hermite(p0, m0, p1, m1, double(k) / n));
  return out;
}

std::vector<Bump> silhouette_bumps(const Polygon2& sil, const SkeletonParams& params) {
  std::vector<Bump> bumps;
  if (sil.size() < 3 || polygon_area(sil) <= 0.0) return bumps;
  // Uniform, counter-clockwise resampling of the closed boundary.
  std::vector<glm::dvec2> closed = sil;
  double signed_area = 0.0;
  for (size_t i = 0, j = sil.size() - 1; i < sil.size(); j = i++) signed_area += sil[j].x * sil[i].y - sil[i].x * sil[j].y;
  if (signed_area < 0) std::reverse(closed.begin(), closed.end());
  closed.push_back(closed.front());
  Polyline2 line(closed);
  const int n = std::max(64, params.samples);
  const double ds = line.length() / n;
  std::vector<glm::dvec2> p(static_cast<size_t>(n)), tangent(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) p[size_t(k)] = line.at(double(k) / n);
  const int w = std::max(1, params.window);
  auto at = [&](int k) { return p[size_t(((k % n) + n) % n)]; };
  std::vector<double> heading(static_cast<size_t>(n)), kappa(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) {
    glm::dvec2 d = at(k + w) - at(k - w);
    heading[size_t(k)] = std::atan2(d.y, d.x);
    tangent[size_t(k)] = glm::length(d) > 0 ? glm::normalize(d) : glm::dvec2(1, 0);
  }
  const double pi = 3.14159265358979323846;
  for (int k = 0; k < n; ++k) {
    double dth = heading[size_t((k + w) % n)] - heading[size_t(((k - w) % n + n) % n)];
    dth = std::remainder(dth, 2.0 * pi);
    kappa[size_t(k)] = dth / (2.0 * w * ds);
  }
  // Convex runs whose curvature beats `significance` times that of the circle of the same
  // perimeter; one bump per run, at its curvature maximum.
  const double threshold = params.significance * 2.0 * pi / line.length();
  int start = -1;
  for (int k = 0; k < n; ++k)
    if (kappa[size_t(k)] <= threshold) { start = k; break; }
  if (start < 0) start = 0;  // everything is a bump: the whole outline is one run
  for (int k = 1; k <= n; ++k) {
    int first = start + k;
    if (kappa[size_t(first % n)] <= threshold) continue;
    int best = first, last = first;
    while (last + 1 < start + n + 1 && kappa[size_t((last + 1) % n)] > threshold) {
      ++last;
      if (kappa[size_t(last % n)] > kappa[size_t(best % n)]) best = last;
    }
    k = last - start;
    // The middle of the run: for a round bump its centre of curvature is the bump's centre
    // and its normal the bump's axis (the maximum can sit anywhere on a circular arc).
    int b = ((first + last) / 2) % n;
    if (kappa[size_t(b)] <= threshold) b = best % n;
    double r = 1.0 / kappa[size_t(b)];
    glm::dvec2 normal(tangent[size_t(b)].y, -tangent[size_t(b)].x);  // outward (CCW outline)
    Bump bump;
    bump.end = p[size_t(b)] - r * normal;
    bump.tangent = normal;
    bump.radius = r;
    if (point_in_polygon(sil, bump.end)) bumps.push_back(bump);
  }
  glm::dvec2 c(0.0);
  for (glm::dvec2 q : sil) c += q;
  c /= double(sil.size());
  std::sort(bumps.begin(), bumps.end(), [&](const Bump& a, const Bump& b) {
    return std::atan2(a.end.y - c.y, a.end.x - c.x) < std::atan2(b.end.y - c.y, b.end.x - c.x);
  });
  return bumps;
}

}  // namespace forest
