#include "generators/bake/hull/hull_nearest.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace forest {

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

MeshNearest make_mesh_nearest(const Mesh& mesh) {
  MeshNearest m;
  m.mesh = &mesh;
  const size_t ntri = mesh.indices.size() / 3;
  if (ntri == 0) return m;
  std::vector<glm::vec3> centroid(ntri), tlo(ntri), thi(ntri);
  for (size_t t = 0; t < ntri; ++t) {
    glm::vec3 a = mesh.vertices[mesh.indices[3 * t]].position;
    glm::vec3 b = mesh.vertices[mesh.indices[3 * t + 1]].position;
    glm::vec3 c = mesh.vertices[mesh.indices[3 * t + 2]].position;
    centroid[t] = (a + b + c) / 3.0f;
    tlo[t] = glm::min(a, glm::min(b, c));
    thi[t] = glm::max(a, glm::max(b, c));
  }
  m.tris.resize(ntri);
  for (size_t t = 0; t < ntri; ++t) m.tris[t] = uint32_t(t);

  // Iterative build (explicit stack: no recursion depth to worry about); median split along
  // the widest axis of the centroids' box, ties by triangle index: deterministic.
  constexpr uint32_t kLeafSize = 4;
  struct Task { uint32_t node, first, count; };
  m.nodes.push_back({});
  std::vector<Task> stack = {{0, 0, uint32_t(ntri)}};
  while (!stack.empty()) {
    Task task = stack.back();
    stack.pop_back();
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    glm::vec3 clo = lo, chi = hi;
    for (uint32_t k = task.first; k < task.first + task.count; ++k) {
      uint32_t t = m.tris[k];
      lo = glm::min(lo, tlo[t]), hi = glm::max(hi, thi[t]);
      clo = glm::min(clo, centroid[t]), chi = glm::max(chi, centroid[t]);
    }
    m.nodes[task.node].lo = lo;
    m.nodes[task.node].hi = hi;
    if (task.count <= kLeafSize) {
      m.nodes[task.node].first = task.first;
      m.nodes[task.node].count = task.count;
      continue;
    }
    glm::vec3 ext = chi - clo;
    int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
    uint32_t half = task.count / 2;
    auto begin = m.tris.begin() + task.first;
    std::nth_element(begin, begin + half, begin + task.count, [&](uint32_t a, uint32_t b) {
      return centroid[a][axis] < centroid[b][axis] || (centroid[a][axis] == centroid[b][axis] && a < b);
    });
    uint32_t left = uint32_t(m.nodes.size()), right = left + 1;
    m.nodes.push_back({});
    m.nodes.push_back({});
    m.nodes[task.node].left = left;
    m.nodes[task.node].right = right;
    stack.push_back({right, task.first + half, task.count - half});
    stack.push_back({left, task.first, half});
  }
  return m;
}

namespace {

float box_distance2(const MeshNearest::Node& n, glm::vec3 q) {
  glm::vec3 d = glm::max(glm::max(n.lo - q, q - n.hi), glm::vec3(0.0f));
  return glm::dot(d, d);
}

}  // namespace

NearestHit nearest_on_mesh(const MeshNearest& m, glm::vec3 q) {
  NearestHit hit;
  if (!m.mesh || m.nodes.empty()) return hit;
  const Mesh& mesh = *m.mesh;
  float best = std::numeric_limits<float>::max();
  glm::vec3 best_bary(1, 0, 0);
  // Depth-first, nearer child first; a box is skipped once it is farther than the best hit.
  // The stack holds at most one pending sibling per level.
  std::vector<std::pair<float, uint32_t>> stack;
  stack.reserve(64);
  stack.push_back({box_distance2(m.nodes[0], q), 0});
  while (!stack.empty()) {
    auto [d2box, ni] = stack.back();
    stack.pop_back();
    if (d2box > best) continue;
    const MeshNearest::Node& n = m.nodes[ni];
    if (n.count > 0) {
      for (uint32_t k = n.first; k < n.first + n.count; ++k) {
        uint32_t t = m.tris[k];
        glm::vec3 bary;
        glm::vec3 p = closest_on_triangle(q, mesh.vertices[mesh.indices[3 * t]].position,
                                          mesh.vertices[mesh.indices[3 * t + 1]].position,
                                          mesh.vertices[mesh.indices[3 * t + 2]].position, &bary);
        glm::vec3 d = p - q;
        float d2 = glm::dot(d, d);
        if (d2 < best || (d2 == best && t < hit.triangle)) best = d2, best_bary = bary, hit.point = p, hit.triangle = t;
      }
      continue;
    }
    float dl = box_distance2(m.nodes[n.left], q), dr = box_distance2(m.nodes[n.right], q);
    if (dl <= dr) {
      stack.push_back({dr, n.right});
      stack.push_back({dl, n.left});
    } else {
      stack.push_back({dl, n.left});
      stack.push_back({dr, n.right});
    }
  }
  hit.distance = std::sqrt(best);
  const uint32_t* tri = &mesh.indices[3 * size_t(hit.triangle)];
  glm::vec3 nrm = best_bary.x * mesh.vertices[tri[0]].normal + best_bary.y * mesh.vertices[tri[1]].normal +
                  best_bary.z * mesh.vertices[tri[2]].normal;
  if (!(glm::dot(nrm, nrm) > 1e-20f)) {
    nrm = glm::cross(mesh.vertices[tri[1]].position - mesh.vertices[tri[0]].position,
                     mesh.vertices[tri[2]].position - mesh.vertices[tri[0]].position);
  }
  hit.normal = glm::dot(nrm, nrm) > 1e-30f ? glm::normalize(nrm) : glm::vec3(0, 1, 0);
  return hit;
}

}  // namespace forest
