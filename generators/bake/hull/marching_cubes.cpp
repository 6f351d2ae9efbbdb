#include "generators/bake/hull/marching_cubes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace forest {

namespace {

// Cube corner b sits at offset (b & 1, (b >> 1) & 1, (b >> 2) & 1) from the cell's origin.
glm::ivec3 corner_offset(int b) { return {b & 1, (b >> 1) & 1, (b >> 2) & 1}; }

struct CubeTopology {
  // The 12 edges: corners (lo, hi) differing in one axis bit, lo < hi.
  std::array<std::array<int, 2>, 12> edge_corners{};
  std::array<int, 12> edge_axis{};
  std::array<std::array<int, 8>, 8> edge_of{};  // corner pair -> edge id (-1 if none)
  // The 6 faces: corners counter-clockwise seen from outside the cube.
  std::array<std::array<int, 4>, 6> face_corners{};
};

// Built from geometry rather than typed in, so there is no table to get wrong.
CubeTopology make_topology() {
  CubeTopology t;
  for (auto& row : t.edge_of) row.fill(-1);
  int e = 0;
  for (int b = 0; b < 8; ++b)
    for (int axis = 0; axis < 3; ++axis)
      if (!(b & (1 << axis))) {
        int h = b | (1 << axis);
        t.edge_corners[e] = {b, h};
        t.edge_axis[e] = axis;
        t.edge_of[b][h] = t.edge_of[h][b] = e;
        ++e;
      }
  int f = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      glm::vec3 n(0.0f);
      n[axis] = side ? 1.0f : -1.0f;
      std::array<int, 4> c{};
      int k = 0;
      for (int b = 0; b < 8; ++b)
        if (((b >> axis) & 1) == side) c[k++] = b;
      // c is in bit order: 00, 10, 01, 11 over the two other axes; walk the square.
      std::array<int, 4> ring = {c[0], c[1], c[3], c[2]};
      glm::vec3 p0(corner_offset(ring[0])), p1(corner_offset(ring[1])), p2(corner_offset(ring[2]));
      if (glm::dot(glm::cross(p1 - p0, p2 - p1), n) < 0.0f) std::swap(ring[1], ring[3]);
      t.face_corners[f++] = ring;
    }
  return t;
}

const CubeTopology& topology() {
  static const CubeTopology t = make_topology();
  return t;
}

}  // namespace

Mesh marching_cubes(const ScalarGrid& grid, float iso, const std::function<float(glm::vec3)>& field) {
  const glm::ivec3 n = grid.size;
  if (n.x < 0 || n.y < 0 || n.z < 0 ||
      grid.values.size() != size_t(n.x) * size_t(n.y) * size_t(n.z))
    throw std::invalid_argument("marching_cubes: grid size does not match its values");
  Mesh mesh;
  if (n.x < 2 || n.y < 2 || n.z < 2) return mesh;
  const CubeTopology& topo = topology();

  // One vertex per crossed grid edge, shared by the up to four cells around it. Key: the
  // edge's lower grid point * 3 + axis. Vertices are created in cell order: deterministic.
  std::unordered_map<uint64_t, uint32_t> edge_vertex;
  auto vertex_on = [&](glm::ivec3 cell, int edge) -> uint32_t {
    glm::ivec3 a = cell + corner_offset(topo.edge_corners[edge][0]);
    glm::ivec3 b = cell + corner_offset(topo.edge_corners[edge][1]);
    uint64_t key = uint64_t(grid.index(a.x, a.y, a.z)) * 3u + uint64_t(topo.edge_axis[edge]);
    auto [it, fresh] = edge_vertex.try_emplace(key, uint32_t(mesh.vertices.size()));
    if (fresh) {
      // Always interpolated from the lower to the upper grid point, whichever cell asks.
      double va = double(grid.at(a.x, a.y, a.z)), vb = double(grid.at(b.x, b.y, b.z));
      const glm::dvec3 pa(grid.point(a.x, a.y, a.z)), pb(grid.point(b.x, b.y, b.z));
      double t = (va == vb) ? 0.5 : (double(iso) - va) / (vb - va);
      t = std::clamp(t, 0.0, 1.0);
      if (field) {
        // Illinois regula falsi on g(t) = field - iso, bracketed by the two samples.
        double t0 = 0.0, g0 = va - iso, t1 = 1.0, g1 = vb - iso;
        int side = 0;
        for (int it = 0; it < 8 && g0 != g1; ++it) {
          t = std::clamp((t0 * g1 - t1 * g0) / (g1 - g0), 0.0, 1.0);
          double g = double(field(glm::vec3(pa + t * (pb - pa)))) - iso;
          if (g == 0.0) break;
          if ((g > 0.0) == (g0 > 0.0)) {
            t0 = t, g0 = g;
            if (side == -1) g1 *= 0.5;
            side = -1;
          } else {
            t1 = t, g1 = g;
            if (side == 1) g0 *= 0.5;
            side = 1;
          }
        }
      }
      Vertex v;
      v.position = glm::vec3(pa + t * (pb - pa));
      mesh.vertices.push_back(v);
    }
    return it->second;
  };

  for (int k = 0; k + 1 < n.z; ++k)
    for (int j = 0; j + 1 < n.y; ++j)
      for (int i = 0; i + 1 < n.x; ++i) {
        const glm::ivec3 cell(i, j, k);
        std::array<double, 8> v{};
        int inside_count = 0;
        for (int b = 0; b < 8; ++b) {
          glm::ivec3 p = cell + corner_offset(b);
          v[b] = double(grid.at(p.x, p.y, p.z)) - double(iso);
          inside_count += v[b] >= 0.0;
        }
        if (inside_count == 0 || inside_count == 8) continue;
        auto in = [&](int b) { return v[b] >= 0.0; };

        // Directed face segments: on every face, walking its corners counter-clockwise from
        // outside, a segment runs from a "fall" crossing (inside -> outside) to a "rise"
        // crossing (outside -> inside). Seen from the neighbouring cell the walk reverses, so
        // the shared segment is traversed in the opposite direction: consistent winding.
        std::array<int, 12> next;
        next.fill(-1);
        for (const auto& q : topo.face_corners) {
          int crossings = 0;
          for (int e = 0; e < 4; ++e) crossings += in(q[e]) != in(q[(e + 1) & 3]);
          if (crossings == 0) continue;
          auto edge = [&](int e) { return topo.edge_of[q[e & 3]][q[(e + 1) & 3]]; };
          bool connect_inside = false;
          if (crossings == 4) {
            // Saddle: decide by the face-centre value (mean of the four samples, summed in
            // sorted order so both cells sharing the face get the identical bits).
            std::array<double, 4> s = {v[q[0]], v[q[1]], v[q[2]], v[q[3]]};
            std::sort(s.begin(), s.end());
            connect_inside = (s[0] + s[1]) + (s[2] + s[3]) >= 0.0;
          }
          for (int c = 0; c < 4; ++c) {
            if (crossings == 2 || !connect_inside) {
              // Cut around inside corner q[c]: fall on edge c -> rise on edge c - 1.
              if (in(q[c]) && !in(q[(c + 1) & 3])) {
                // Find the rise that closes this inside run (the run may span several corners).
                int r = c;
                for (int s = 0; s < 4; ++s) {
                  int prev = (r + 3) & 3;
                  if (!in(q[prev])) break;
                  r = prev;
                }
                next[edge(c)] = edge(r + 3);
              }
            } else {
              // Cut around outside corner q[c]: fall on edge c - 1 -> rise on edge c.
              if (!in(q[c])) next[edge(c + 3)] = edge(c);
            }
          }
        }

        // Follow the segments into closed loops and triangulate each.
        std::array<bool, 12> used{};
        for (int start = 0; start < 12; ++start) {
          if (next[start] < 0 || used[start]) continue;
          std::array<uint32_t, 12> loop{};
          int len = 0;
          int e = start;
          while (e >= 0 && !used[e] && len < 12) {
            used[e] = true;
            loop[len++] = vertex_on(cell, e);
            e = next[e];
          }
          if (e != start || len < 3)
            throw std::logic_error("marching_cubes: open contour in a cell");
          // The loop runs clockwise seen from outside: emit triangles reversed.
          auto tri = [&](uint32_t a, uint32_t b, uint32_t c) {
            mesh.indices.insert(mesh.indices.end(), {a, c, b});
          };
          if (len == 3) {
            tri(loop[0], loop[1], loop[2]);
          } else if (len == 4) {
            // Split along the shorter diagonal: fewer slivers.
            auto d2 = [&](int a, int b) {
              glm::vec3 d = mesh.vertices[loop[a]].position - mesh.vertices[loop[b]].position;
              return glm::dot(d, d);
            };
            if (d2(0, 2) <= d2(1, 3)) {
              tri(loop[0], loop[1], loop[2]);
              tri(loop[0], loop[2], loop[3]);
            } else {
              tri(loop[1], loop[2], loop[3]);
              tri(loop[1], loop[3], loop[0]);
            }
          } else {
            // Five to twelve sides: a fan around the centroid stays valid for non-planar and
            // non-convex loops where a corner fan would fold.
            glm::dvec3 c(0.0);
            for (int s = 0; s < len; ++s) c += glm::dvec3(mesh.vertices[loop[s]].position);
            Vertex centre;
            centre.position = glm::vec3(c / double(len));
            uint32_t ci = uint32_t(mesh.vertices.size());
            mesh.vertices.push_back(centre);
            for (int s = 0; s < len; ++s) tri(ci, loop[s], loop[(s + 1) % len]);
          }
        }
      }
  return mesh;
}

}  // namespace forest
