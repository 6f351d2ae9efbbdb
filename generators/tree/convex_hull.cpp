#include "generators/tree/convex_hull.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <utility>

namespace forest {

namespace {

// Points are snapped to an integer grid of 2^20 steps over the longest side of their box.
// Every decision (is a point above a face?) is then an exact integer determinant: a
// tolerance would let near-coplanar faces (leaves spaced along a shoot, repeated leaf
// positions) see a point inconsistently, pinch the horizon at a vertex and fold the hull.
constexpr double kGridSteps = double(1 << 20);

using Int3 = glm::i64vec3;

Int3 cross(Int3 u, Int3 v) { return {u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x}; }

// Sign of det(b − a, c − a, p − a): > 0 when p is above the face a, b, c (counter-clockwise
// seen from above). Cross components stay below 2^42, so the products fit in 128 bits.
__int128 det(Int3 a, Int3 b, Int3 c, Int3 p) {
  Int3 n = cross(b - a, c - a), w = p - a;
  return __int128(n.x) * w.x + __int128(n.y) * w.y + __int128(n.z) * w.z;
}

int orient(Int3 a, Int3 b, Int3 c, Int3 p) {
  __int128 d = det(a, b, c, p);
  return d > 0 ? 1 : d < 0 ? -1 : 0;
}

struct Face {
  std::array<uint32_t, 3> v{};
  glm::dvec3 normal{0.0};  // unit, outward, in grid units
  double offset = 0.0;
  std::vector<uint32_t> outside;  // points above this face, not yet on the hull
  bool alive = true;
};

uint64_t edge_key(uint32_t a, uint32_t b) { return (uint64_t(a) << 32) | b; }

struct Builder {
  std::vector<Int3> q;  // snapped points, grid units
  std::vector<Face> faces;
  std::unordered_map<uint64_t, uint32_t> edge_face;  // directed edge a→b → the face holding it

  bool above(const Face& f, uint32_t i) const { return orient(q[f.v[0]], q[f.v[1]], q[f.v[2]], q[i]) > 0; }
  // Only for choosing the farthest point; the combinatorics use `above`.
  double distance(const Face& f, uint32_t i) const { return glm::dot(f.normal, glm::dvec3(q[i])) - f.offset; }

  // A face a, b, c (counter-clockwise from outside). The cross product of grid vectors is
  // exact in doubles (components below 2^42).
  uint32_t add_face(uint32_t a, uint32_t b, uint32_t c) {
    Face f;
    f.v = {a, b, c};
    glm::dvec3 n(cross(q[b] - q[a], q[c] - q[a]));
    f.normal = n / glm::length(n);  // never zero: see expand()
    f.offset = glm::dot(f.normal, glm::dvec3(q[a]));
    const uint32_t id = uint32_t(faces.size());
    faces.push_back(std::move(f));
    for (int k = 0; k < 3; ++k) edge_face[edge_key(faces[id].v[k], faces[id].v[(k + 1) % 3])] = id;
    return id;
  }

  // Gives each candidate to the first face it lies above; the rest are inside (or on) the
  // hull built so far and are dropped for good.
  void assign(const std::vector<uint32_t>& candidates, const std::vector<uint32_t>& to, uint32_t skip) {
    for (uint32_t i : candidates) {
      if (i == skip) continue;
      for (uint32_t f : to)
        if (above(faces[f], i)) {
          faces[f].outside.push_back(i);
          break;
        }
    }
  }

  // Adds the farthest outside point of face `start`: the faces it sees (found by walking
  // across edges from `start`) are replaced by a fan from the point to their horizon. With
  // exact tests the faces strictly seen from a point outside a convex polytope form a disk,
  // so the horizon is one simple cycle; and no new face is degenerate, as the point would
  // then lie in the planes of both faces at its horizon edge, seen by neither.
  std::vector<uint32_t> expand(uint32_t start) {
    const Face& s = faces[start];
    uint32_t eye = s.outside[0];
    for (uint32_t i : s.outside)
      if (distance(s, i) > distance(s, eye)) eye = i;
    std::vector<uint32_t> visible = {start}, horizon;  // horizon: pairs a, b
    std::vector<uint8_t> seen(faces.size(), 0);
    seen[start] = 1;
    for (size_t k = 0; k < visible.size(); ++k)
      for (int e = 0; e < 3; ++e) {
        uint32_t a = faces[visible[k]].v[e], b = faces[visible[k]].v[(e + 1) % 3];
        uint32_t g = edge_face.at(edge_key(b, a));  // the hull is closed
        if (seen[g]) continue;                       // visible: the edge goes with both faces
        if (above(faces[g], eye)) {
          seen[g] = 1;
          visible.push_back(g);
        } else {
          horizon.push_back(a), horizon.push_back(b);  // visibility is g's alone: g stays
        }
      }
    std::vector<uint32_t> orphans;
    for (uint32_t f : visible) {
      faces[f].alive = false;
      orphans.insert(orphans.end(), faces[f].outside.begin(), faces[f].outside.end());
      faces[f].outside.clear();
      for (int e = 0; e < 3; ++e) edge_face.erase(edge_key(faces[f].v[e], faces[f].v[(e + 1) % 3]));
    }
    std::vector<uint32_t> added;
    for (size_t h = 0; h < horizon.size(); h += 2) added.push_back(add_face(horizon[h], horizon[h + 1], eye));
    assign(orphans, added, eye);
    return added;
  }
};

// Four points spanning a volume: the farthest pair of the six axis extremes, then the
// farthest from their line, then the farthest from their plane. False when there are none.
bool initial_simplex(const Builder& b, std::array<uint32_t, 4>& s) {
  const size_t n = b.q.size();
  std::array<uint32_t, 6> ext{};
  for (uint32_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) {
      if (b.q[i][a] < b.q[ext[size_t(2 * a)]][a]) ext[size_t(2 * a)] = i;
      if (b.q[i][a] > b.q[ext[size_t(2 * a + 1)]][a]) ext[size_t(2 * a + 1)] = i;
    }
  int64_t best = -1;
  for (uint32_t i : ext)
    for (uint32_t j : ext) {
      Int3 d = b.q[i] - b.q[j];
      if (int64_t l = d.x * d.x + d.y * d.y + d.z * d.z; l > best) best = l, s[0] = i, s[1] = j;
    }
  if (best <= 0) return false;
  double far = 0.0;
  for (uint32_t i = 0; i < n; ++i) {
    Int3 c = cross(b.q[s[1]] - b.q[s[0]], b.q[i] - b.q[s[0]]);
    if (double l = glm::length(glm::dvec3(c)); l > far) far = l, s[2] = i;
  }
  if (far <= 0.0) return false;  // exact: the cross product's components are exact in doubles
  __int128 height = 0;
  for (uint32_t i = 0; i < n; ++i) {
    __int128 d = det(b.q[s[0]], b.q[s[1]], b.q[s[2]], b.q[i]);
    if (d < 0) d = -d;
    if (d > height) height = d, s[3] = i;
  }
  return height > 0;
}

}  // namespace

ConvexHull convex_hull(std::span<const glm::vec3> points) {
  ConvexHull hull;
  if (points.size() < 4) return hull;
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (glm::vec3 p : points) lo = glm::min(lo, glm::dvec3(p)), hi = glm::max(hi, glm::dvec3(p));
  const double step = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}) / kGridSteps;
  if (!(step > 0.0)) return hull;
  hull.tolerance = step;
  Builder b;
  b.q.reserve(points.size());
  for (glm::vec3 p : points) b.q.push_back(Int3(glm::round((glm::dvec3(p) - lo) / step)));
  std::array<uint32_t, 4> s{};
  if (!initial_simplex(b, s)) return hull;
  // The base triangle s0 s1 s2 facing away from s3, then the three sides to s3.
  if (orient(b.q[s[0]], b.q[s[1]], b.q[s[2]], b.q[s[3]]) > 0) std::swap(s[1], s[2]);
  std::vector<uint32_t> first = {b.add_face(s[0], s[1], s[2]), b.add_face(s[0], s[3], s[1]),
                                 b.add_face(s[1], s[3], s[2]), b.add_face(s[2], s[3], s[0])};
  std::vector<uint32_t> rest;
  for (uint32_t i = 0; i < points.size(); ++i)
    if (std::find(s.begin(), s.end(), i) == s.end()) rest.push_back(i);
  b.assign(rest, first, std::numeric_limits<uint32_t>::max());
  std::vector<uint32_t> work = first;
  while (!work.empty()) {
    uint32_t f = work.back();
    work.pop_back();
    if (!b.faces[f].alive || b.faces[f].outside.empty()) continue;
    for (uint32_t g : b.expand(f)) work.push_back(g);
  }
  // Planes back in metres: x = lo + step · grid, so n·grid ≤ d becomes n·x ≤ step · d + n·lo.
  for (const Face& f : b.faces)
    if (f.alive) {
      hull.triangles.push_back({f.v[0], f.v[1], f.v[2]});
      hull.planes.push_back({f.normal, step * f.offset + glm::dot(f.normal, lo)});
    }
  return hull;
}

double depth_below_hull(const ConvexHull& hull, glm::dvec3 p) {
  if (hull.planes.empty()) return 0.0;
  double depth = std::numeric_limits<double>::max();
  for (const HullPlane& h : hull.planes) depth = std::min(depth, h.offset - glm::dot(h.normal, p));
  return std::max(depth, 0.0);
}

}  // namespace forest
