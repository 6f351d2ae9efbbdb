#include "generators/mesh/junction.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace forest {

namespace {

glm::dvec3 face_normal(std::span<const glm::dvec3> p, const std::array<uint32_t, 3>& f) {
  return glm::cross(p[f[1]] - p[f[0]], p[f[2]] - p[f[0]]);
}

}  // namespace

bool convex_hull(std::span<const glm::dvec3> p, std::vector<std::array<uint32_t, 3>>* faces) {
  faces->clear();
  const size_t n = p.size();
  if (n < 4) return false;
  double scale = 0.0;
  for (const glm::dvec3& q : p) scale = std::max(scale, glm::length(q - p[0]));
  if (!(scale > 0.0)) return false;
  const double eps = 1e-12 * scale;

  // Initial tetrahedron: far apart points, so that it is well shaped.
  uint32_t i0 = 0, i1 = 0, i2 = 0, i3 = 0;
  for (uint32_t i = 0; i < n; ++i)
    if (glm::length(p[i] - p[i0]) > glm::length(p[i1] - p[i0])) i1 = i;
  double best = 0.0;
  for (uint32_t i = 0; i < n; ++i) {
    double d = glm::length(glm::cross(p[i1] - p[i0], p[i] - p[i0]));
    if (d > best) best = d, i2 = i;
  }
  if (best <= eps * scale) return false;
  glm::dvec3 nrm = glm::normalize(glm::cross(p[i1] - p[i0], p[i2] - p[i0]));
  best = 0.0;
  for (uint32_t i = 0; i < n; ++i) {
    double d = std::abs(glm::dot(nrm, p[i] - p[i0]));
    if (d > best) best = d, i3 = i;
  }
  if (best <= 1e-9 * scale) return false;

  std::vector<std::array<uint32_t, 3>> hull;
  if (glm::dot(nrm, p[i3] - p[i0]) > 0.0) std::swap(i1, i2);  // i3 behind (i0, i1, i2)
  hull = {{i0, i1, i2}, {i0, i3, i1}, {i1, i3, i2}, {i2, i3, i0}};

  std::vector<char> visible;
  std::map<std::pair<uint32_t, uint32_t>, int> edge_count;
  for (uint32_t i = 0; i < n; ++i) {
    if (i == i0 || i == i1 || i == i2 || i == i3) continue;
    visible.assign(hull.size(), 0);
    bool any = false;
    for (size_t f = 0; f < hull.size(); ++f) {
      glm::dvec3 fn = face_normal(p, hull[f]);
      double len = glm::length(fn);
      if (len <= 0.0) continue;
      if (glm::dot(fn / len, p[i] - p[hull[f][0]]) > eps) visible[f] = 1, any = true;
    }
    if (!any) continue;  // inside, or on the hull within rounding
    // Horizon: directed edges of visible faces whose reverse is not in a visible face.
    edge_count.clear();
    for (size_t f = 0; f < hull.size(); ++f)
      if (visible[f])
        for (int k = 0; k < 3; ++k) edge_count[{hull[f][k], hull[f][(k + 1) % 3]}]++;
    std::vector<std::array<uint32_t, 3>> next;
    next.reserve(hull.size() + 8);
    for (size_t f = 0; f < hull.size(); ++f)
      if (!visible[f]) next.push_back(hull[f]);
    for (const auto& [edge, count] : edge_count)
      if (!edge_count.count({edge.second, edge.first})) next.push_back({edge.first, edge.second, i});
    hull.swap(next);
  }
  *faces = std::move(hull);
  return true;
}

bool join_rings(glm::vec3 center, std::span<const JunctionRing> rings,
                std::vector<std::array<RingVertex, 3>>* triangles) {
  triangles->clear();
  if (rings.size() < 2) return false;
  // Points: every ring vertex projected onto the unit sphere, then one pole per ring.
  std::vector<glm::dvec3> pts;
  std::vector<RingVertex> owner;  // ring vertex of each projected point
  const glm::dvec3 c(center);
  for (uint32_t r = 0; r < rings.size(); ++r) {
    if (rings[r].points.size() < 3) return false;
    for (uint32_t k = 0; k < rings[r].points.size(); ++k) {
      glm::dvec3 d = glm::dvec3(rings[r].points[k]) - c;
      double len = glm::length(d);
      if (!(len > 0.0)) return false;
      pts.push_back(d / len);
      owner.push_back({r, k});
    }
  }
  // Each cap's pole, lifted a little above the plane of its (co-circular) ring points: the
  // cap becomes a low tent, so that the hull triangulates it as a fan from the pole. A pole
  // on the sphere itself would make the fan's triangles reach twice as far as the cap for
  // rings with few sides.
  const uint32_t first_pole = uint32_t(pts.size());
  for (uint32_t r = 0, at = 0; r < rings.size(); ++r) {
    glm::dvec3 a(rings[r].axis);
    double len = glm::length(a);
    if (!(len > 0.0)) return false;
    a /= len;
    double h = 0.0;  // height of the ring's plane
    for (size_t k = 0; k < rings[r].points.size(); ++k) h += glm::dot(pts[at + k], a);
    h /= double(rings[r].points.size());
    at += uint32_t(rings[r].points.size());
    if (!(h > 0.0 && h < 1.0)) return false;
    pts.push_back(a * (h + 0.1 * (1.0 - h)));
  }
  std::vector<std::array<uint32_t, 3>> faces;
  if (!convex_hull(pts, &faces)) return false;

  // Which way each ring runs about its axis: the junction must use its edges clockwise.
  std::vector<int> ccw(rings.size());
  for (uint32_t r = 0; r < rings.size(); ++r) {
    const auto& q = rings[r].points;
    glm::dvec3 mid(0.0), area(0.0);
    for (const glm::vec3& v : q) mid += glm::dvec3(v);
    mid /= double(q.size());
    for (size_t k = 0; k < q.size(); ++k)
      area += glm::cross(glm::dvec3(q[k]) - mid, glm::dvec3(q[(k + 1) % q.size()]) - mid);
    ccw[r] = glm::dot(area, glm::dvec3(rings[r].axis)) > 0.0 ? 1 : -1;
  }

  // Keep the faces without poles; the ones with a pole must be exactly the cap fans.
  std::vector<size_t> fan(rings.size(), 0);
  std::map<std::pair<uint64_t, uint64_t>, int> directed;  // edge -> uses
  auto key = [](RingVertex v) { return (uint64_t(v.ring) << 32) | v.index; };
  for (const auto& f : faces) {
    int poles = 0;
    uint32_t pole_at = 0;
    for (int k = 0; k < 3; ++k)
      if (f[k] >= first_pole) ++poles, pole_at = uint32_t(k);
    if (poles > 1) return triangles->clear(), false;
    if (poles == 1) {
      uint32_t r = f[pole_at] - first_pole;
      RingVertex a = owner[f[(pole_at + 1) % 3]], b = owner[f[(pole_at + 2) % 3]];
      uint32_t m = uint32_t(rings[r].points.size());
      // Seen from outside the cap runs counter-clockwise about the axis: a -> b is a step
      // of +1 in the ring's own order when it runs ccw, -1 when it runs cw.
      uint32_t expect = ccw[r] > 0 ? (a.index + 1) % m : (a.index + m - 1) % m;
      if (a.ring != r || b.ring != r || b.index != expect) return triangles->clear(), false;
      ++fan[r];
      continue;
    }
    std::array<RingVertex, 3> t{owner[f[0]], owner[f[1]], owner[f[2]]};
    if (t[0].ring == t[1].ring && t[1].ring == t[2].ring) return triangles->clear(), false;  // in a cap
    for (int k = 0; k < 3; ++k) directed[{key(t[k]), key(t[(k + 1) % 3])}]++;
    triangles->push_back(t);
  }
  // Every cap is a full fan, so every ring vertex is on the hull.
  for (uint32_t r = 0; r < rings.size(); ++r)
    if (fan[r] != rings[r].points.size()) return triangles->clear(), false;
  // Ring edges: once, clockwise about the axis; every other edge: once each way.
  for (const auto& [edge, uses] : directed) {
    RingVertex a{uint32_t(edge.first >> 32), uint32_t(edge.first)};
    RingVertex b{uint32_t(edge.second >> 32), uint32_t(edge.second)};
    bool reverse_used = directed.count({edge.second, edge.first}) > 0;
    if (uses != 1) return triangles->clear(), false;
    if (a.ring == b.ring) {
      uint32_t m = uint32_t(rings[a.ring].points.size());
      uint32_t cw_next = ccw[a.ring] > 0 ? (a.index + m - 1) % m : (a.index + 1) % m;
      uint32_t ccw_next = ccw[a.ring] > 0 ? (a.index + 1) % m : (a.index + m - 1) % m;
      if (b.index == cw_next && !reverse_used) continue;  // a ring edge
      if (b.index == ccw_next) return triangles->clear(), false;  // ring edge, wrong way
    }
    if (!reverse_used) return triangles->clear(), false;  // a hole inside the junction
  }
  return true;
}

}  // namespace forest
