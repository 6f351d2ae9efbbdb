#include "generators/bake/hull_nearest.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace forest {

namespace {

constexpr double kMaxCells = 2.0e6;

glm::ivec3 cell_of(const MeshNearest& m, glm::vec3 q) {
  glm::vec3 c = glm::floor((q - m.origin) / m.cell);
  c = glm::clamp(c, glm::vec3(0.0f), glm::vec3(m.cells - 1));
  return glm::ivec3(c);
}

size_t flat(const MeshNearest& m, glm::ivec3 c) {
  return (size_t(c.z) * size_t(m.cells.y) + size_t(c.y)) * size_t(m.cells.x) + size_t(c.x);
}

}  // namespace

glm::vec3 closest_on_triangle(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c,
                              glm::vec3* bary) {
  auto out = [&](float u, float v, float w) {
    if (bary) *bary = glm::vec3(u, v, w);
    return u * a + v * b + w * c;
  };
  glm::vec3 ab = b - a, ac = c - a, ap = p - a;
  float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0f && d2 <= 0.0f) return out(1, 0, 0);
  glm::vec3 bp = p - b;
  float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0f && d4 <= d3) return out(0, 1, 0);
  float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
    float v = d1 / (d1 - d3);
    return out(1 - v, v, 0);
  }
  glm::vec3 cp = p - c;
  float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0f && d5 <= d6) return out(0, 0, 1);
  float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
    float w = d2 / (d2 - d6);
    return out(1 - w, 0, w);
  }
  float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
    float w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return out(0, 1 - w, w);
  }
  float denom = va + vb + vc;
  if (!(std::abs(denom) > 0.0f)) return out(1, 0, 0);  // degenerate triangle
  float v = vb / denom, w = vc / denom;
  return out(1 - v - w, v, w);
}

MeshNearest make_mesh_nearest(const Mesh& mesh, float cell) {
  MeshNearest m;
  m.mesh = &mesh;
  const size_t ntri = mesh.indices.size() / 3;
  if (ntri == 0) return m;
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  double edge_sum = 0.0;
  for (size_t t = 0; t < ntri; ++t)
    for (int k = 0; k < 3; ++k) {
      glm::vec3 p = mesh.vertices[mesh.indices[3 * t + k]].position;
      glm::vec3 q = mesh.vertices[mesh.indices[3 * t + (k + 1) % 3]].position;
      lo = glm::min(lo, p), hi = glm::max(hi, p);
      edge_sum += glm::length(p - q);
    }
  glm::dvec3 extent = glm::max(glm::dvec3(hi - lo), glm::dvec3(1e-6));
  double c = cell > 0.0f ? double(cell) : 2.0 * edge_sum / double(3 * ntri);
  c = std::max(c, 1e-6);
  for (int guard = 0; guard < 64; ++guard) {
    glm::dvec3 n = glm::floor(extent / c) + 1.0;
    if (n.x * n.y * n.z <= kMaxCells) break;
    c *= 1.5;
  }
  m.cell = float(c);
  m.origin = lo;
  m.cells = glm::ivec3(glm::floor(extent / c)) + 1;

  // Each triangle goes into every cell its bounding box overlaps (two passes: count, fill).
  const size_t ncells = size_t(m.cells.x) * size_t(m.cells.y) * size_t(m.cells.z);
  m.cell_start.assign(ncells + 1, 0);
  auto for_cells = [&](size_t t, auto&& fn) {
    glm::vec3 a = mesh.vertices[mesh.indices[3 * t]].position;
    glm::vec3 b = mesh.vertices[mesh.indices[3 * t + 1]].position;
    glm::vec3 d = mesh.vertices[mesh.indices[3 * t + 2]].position;
    glm::ivec3 l = cell_of(m, glm::min(a, glm::min(b, d))), h = cell_of(m, glm::max(a, glm::max(b, d)));
    for (int z = l.z; z <= h.z; ++z)
      for (int y = l.y; y <= h.y; ++y)
        for (int x = l.x; x <= h.x; ++x) fn(flat(m, {x, y, z}));
  };
  for (size_t t = 0; t < ntri; ++t) for_cells(t, [&](size_t c2) { ++m.cell_start[c2 + 1]; });
  for (size_t c2 = 0; c2 < ncells; ++c2) m.cell_start[c2 + 1] += m.cell_start[c2];
  m.tris.resize(m.cell_start[ncells]);
  std::vector<uint32_t> fill(m.cell_start.begin(), m.cell_start.end() - 1);
  for (size_t t = 0; t < ntri; ++t) for_cells(t, [&](size_t c2) { m.tris[fill[c2]++] = uint32_t(t); });
  return m;
}

NearestHit nearest_on_mesh(const MeshNearest& m, glm::vec3 q) {
  NearestHit hit;
  if (!m.mesh || m.cell_start.empty()) return hit;
  const Mesh& mesh = *m.mesh;
  const glm::ivec3 c0 = cell_of(m, q);
  float best = std::numeric_limits<float>::max();
  glm::vec3 best_bary(1, 0, 0);
  const int max_ring = std::max(m.cells.x, std::max(m.cells.y, m.cells.z));
  for (int ring = 0; ring <= max_ring; ++ring) {
    glm::ivec3 lo = c0 - ring, hi = c0 + ring;
    glm::ivec3 l = glm::max(lo, glm::ivec3(0)), h = glm::min(hi, m.cells - 1);
    for (int z = l.z; z <= h.z; ++z)
      for (int y = l.y; y <= h.y; ++y)
        for (int x = l.x; x <= h.x; ++x) {
          // Only the shell of this ring: the inside was searched before.
          if (x != lo.x && x != hi.x && y != lo.y && y != hi.y && z != lo.z && z != hi.z) continue;
          size_t c = flat(m, {x, y, z});
          for (uint32_t k = m.cell_start[c]; k < m.cell_start[c + 1]; ++k) {
            uint32_t t = m.tris[k];
            glm::vec3 bary;
            glm::vec3 p = closest_on_triangle(q, mesh.vertices[mesh.indices[3 * t]].position,
                                              mesh.vertices[mesh.indices[3 * t + 1]].position,
                                              mesh.vertices[mesh.indices[3 * t + 2]].position, &bary);
            glm::vec3 d = p - q;
            float d2 = glm::dot(d, d);
            if (d2 < best || (d2 == best && t < hit.triangle)) {
              best = d2, best_bary = bary, hit.point = p, hit.triangle = t;
            }
          }
        }
    // Everything not yet searched lies outside the box of cells [lo, hi]; if q is inside
    // that box, it is at least the distance to the box's nearest face away.
    glm::vec3 blo = m.origin + glm::vec3(lo) * m.cell, bhi = m.origin + glm::vec3(hi + 1) * m.cell;
    float margin = std::min({q.x - blo.x, q.y - blo.y, q.z - blo.z, bhi.x - q.x, bhi.y - q.y, bhi.z - q.z});
    if (best < std::numeric_limits<float>::max() && margin > 0.0f && best <= margin * margin) break;
  }
  hit.distance = std::sqrt(best);
  const uint32_t* tri = &mesh.indices[3 * size_t(hit.triangle)];
  glm::vec3 n = best_bary.x * mesh.vertices[tri[0]].normal + best_bary.y * mesh.vertices[tri[1]].normal +
                best_bary.z * mesh.vertices[tri[2]].normal;
  if (!(glm::dot(n, n) > 1e-20f)) {
    n = glm::cross(mesh.vertices[tri[1]].position - mesh.vertices[tri[0]].position,
                   mesh.vertices[tri[2]].position - mesh.vertices[tri[0]].position);
  }
  hit.normal = glm::dot(n, n) > 1e-30f ? glm::normalize(n) : glm::vec3(0, 1, 0);
  return hit;
}

}  // namespace forest
