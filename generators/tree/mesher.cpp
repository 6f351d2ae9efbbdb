#include "generators/tree/mesher.h"

#include <algorithm>
#include <cmath>

#include "generators/tree/frames.h"

namespace forest {

namespace {

constexpr float kPi = 3.14159265358979323846f;

glm::vec3 rotate_about(glm::vec3 v, glm::vec3 k, float angle) {
  float c = std::cos(angle), s = std::sin(angle);
  return v * c + glm::cross(k, v) * s + k * glm::dot(k, v) * (1.0f - c);
}

// A chain: graph nodes swept by one tube. `from_parent`: the first node is the parent the
// chain branches off, so its first ring uses the branch's own radius, not the parent's.
struct Chain {
  std::vector<uint32_t> nodes;
  bool from_parent = false;
};

std::vector<Chain> decompose_chains(const TreeGraph& graph,
                                    const std::vector<std::vector<uint32_t>>& children) {
  std::vector<Chain> chains;
  std::vector<Chain> pending;  // side chains not yet followed, each holding [parent, child]
  for (uint32_t i = 0; i < graph.nodes.size(); ++i)
    if (graph.nodes[i].parent < 0 && !children[i].empty()) pending.push_back(Chain{{i}, false});
  std::reverse(pending.begin(), pending.end());
  while (!pending.empty()) {
    Chain chain = std::move(pending.back());
    pending.pop_back();
    std::vector<Chain> started;
    uint32_t cur = chain.nodes.back();
    while (!children[cur].empty()) {
      // Continue along the thickest child (lowest index on ties: deterministic).
      uint32_t next = children[cur][0];
      for (uint32_t c : children[cur])
        if (graph.nodes[c].radius > graph.nodes[next].radius) next = c;
      for (uint32_t c : children[cur])
        if (c != next) started.push_back(Chain{{cur, c}, true});
      chain.nodes.push_back(next);
      cur = next;
    }
    chains.push_back(std::move(chain));
    // Depth-first order keeps a branch's sub-branches near it in the vertex buffer.
    for (auto it = started.rbegin(); it != started.rend(); ++it) pending.push_back(std::move(*it));
  }
  return chains;
}

struct ChainPoint {
  glm::vec3 position;
  float radius;
  uint32_t node;
};

}  // namespace

int ring_sides(float r, float r_max, const MesherParams& params) {
  int lo = std::max(3, params.min_sides);
  int hi = std::max(lo, params.max_sides);
  if (!(r_max > 0.0f) || !(r > 0.0f)) return lo;
  float s = float(hi) * std::sqrt(std::min(1.0f, r / r_max));
  return std::clamp(int(std::lround(s)), lo, hi);
}

Mesh mesh_branches(const TreeGraph& graph, const MesherParams& params, BranchMeshInfo* info) {
  Mesh mesh;
  if (info) *info = {};
  auto children = children_of(graph);
  std::vector<Chain> chains = decompose_chains(graph, children);
  const float cos_collinear = std::cos(params.collinear_deg * kPi / 180.0f);

  auto radius_of = [&](uint32_t node) {
    return std::max(graph.nodes[node].radius, params.min_radius);
  };
  float r_max = 0.0f;
  for (const Chain& c : chains)
    r_max = std::max(r_max, radius_of(c.from_parent ? c.nodes[1] : c.nodes[0]));

  uint32_t chain_index = 0;
  for (const Chain& chain : chains) {
    // 1. Points, without consecutive duplicates (they would give zero-area triangles).
    std::vector<ChainPoint> pts;
    for (size_t i = 0; i < chain.nodes.size(); ++i) {
      uint32_t node = chain.nodes[i];
      float r = (i == 0 && chain.from_parent) ? radius_of(chain.nodes[1]) : radius_of(node);
      glm::vec3 p = graph.nodes[node].position;
      if (!pts.empty() && glm::length(p - pts.back().position) < 1e-5f) {
        if (i + 1 == chain.nodes.size()) pts.back() = {p, r, node};  // keep the true end
        continue;
      }
      pts.push_back({p, r, node});
    }
    if (pts.size() < 2) continue;

    // 2. Rings: ends always; interior nodes only where the tube bends or changes radius.
    std::vector<ChainPoint> kept{pts[0]};
    for (size_t i = 1; i + 1 < pts.size(); ++i) {
      glm::vec3 in = glm::normalize(pts[i].position - kept.back().position);
      glm::vec3 out = glm::normalize(pts[i + 1].position - pts[i].position);
      float dr = std::abs(pts[i].radius - kept.back().radius);
      if (glm::dot(in, out) < cos_collinear || dr > params.radius_tolerance * kept.back().radius)
        kept.push_back(pts[i]);
    }
    kept.push_back(pts.back());

    const size_t n = kept.size();
    std::vector<glm::vec3> seg(n - 1);
    for (size_t i = 0; i + 1 < n; ++i)
      seg[i] = glm::normalize(kept[i + 1].position - kept[i].position);

    const uint32_t sides = uint32_t(ring_sides(kept[0].radius, r_max, params));
    const float circumference = 2.0f * kPi * kept[0].radius;

    // 3. Sweep with parallel-transported frames: no twist along straight parts, no flips at
    // inflections (Frenet frames have both problems).
    glm::vec3 prev_t = seg[0];
    glm::vec3 normal = any_perpendicular(prev_t);
    float length = 0.0f;
    std::vector<uint32_t> ring_first(n);
    glm::vec3 tangent = prev_t;
    for (size_t i = 0; i < n; ++i) {
      if (i == 0) tangent = seg[0];
      else if (i + 1 == n) tangent = seg[n - 2];
      else {
        glm::vec3 sum = seg[i - 1] + seg[i];
        tangent = glm::length(sum) > 1e-6f ? glm::normalize(sum) : seg[i];
      }
      glm::vec3 axis = glm::cross(prev_t, tangent);
      float s = glm::length(axis);
      if (s > 1e-7f) normal = rotate_about(normal, axis / s, std::atan2(s, glm::dot(prev_t, tangent)));
      normal = glm::normalize(normal - glm::dot(normal, tangent) * tangent);
      glm::vec3 binormal = glm::cross(tangent, normal);  // normal x binormal = tangent
      prev_t = tangent;
      if (i > 0) length += glm::length(kept[i].position - kept[i - 1].position);

      ring_first[i] = uint32_t(mesh.vertices.size());
      for (uint32_t k = 0; k <= sides; ++k) {
        float theta = 2.0f * kPi * float(k % sides) / float(sides);
        glm::vec3 dir = std::cos(theta) * normal + std::sin(theta) * binormal;
        Vertex v;
        v.position = kept[i].position + kept[i].radius * dir;
        v.normal = glm::normalize(dir);
        v.uv = glm::vec2(float(k) / float(sides), length / circumference);
        mesh.vertices.push_back(v);
      }
      if (info)
        info->rings.push_back(TubeRing{kept[i].node, chain_index, kept[i].position, tangent,
                                       kept[i].radius, sides, ring_first[i]});
    }

    // 4. Quads between consecutive rings, counter-clockwise seen from outside:
    // (a_k, a_k+1, b_k) has normal ~ binormal x tangent = normal (outward).
    for (size_t i = 0; i + 1 < n; ++i) {
      uint32_t a = ring_first[i], b = ring_first[i + 1];
      for (uint32_t k = 0; k < sides; ++k) {
        mesh.indices.insert(mesh.indices.end(), {a + k, a + k + 1, b + k});
        mesh.indices.insert(mesh.indices.end(), {a + k + 1, b + k + 1, b + k});
      }
    }

    // 5. A cone closes the tip: apex one radius beyond the last ring.
    const ChainPoint& end = kept.back();
    Vertex apex;
    apex.position = end.position + tangent * end.radius;
    apex.normal = tangent;
    apex.uv = glm::vec2(0.5f, (length + end.radius) / circumference);
    uint32_t apex_index = uint32_t(mesh.vertices.size());
    mesh.vertices.push_back(apex);
    if (info) info->cap_vertices.push_back(apex_index);
    uint32_t last = ring_first[n - 1];
    for (uint32_t k = 0; k < sides; ++k)
      mesh.indices.insert(mesh.indices.end(), {last + k, last + k + 1, apex_index});
    ++chain_index;
  }
  return mesh;
}

Mesh make_leaf_card() {
  // Hexagon outline, counter-clockwise seen from +Z: base, right side, tip, left side.
  const glm::vec2 outline[6] = {{0.0f, 0.0f},   {0.22f, 0.3f},  {0.16f, 0.72f},
                                {0.0f, 1.0f},   {-0.16f, 0.72f}, {-0.22f, 0.3f}};
  Mesh card;
  for (const glm::vec2& p : outline) {
    Vertex v;
    v.position = glm::vec3(p, 0.0f);
    v.normal = glm::vec3(0.0f, 0.0f, 1.0f);
    v.uv = glm::vec2(0.5f + p.x, 1.0f - p.y);  // texture: leaf upright, tip at the top
    card.vertices.push_back(v);
  }
  card.indices = {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 5};  // fan from the base
  return card;
}

glm::vec3 leaf_to_model(const LeafPlacement& leaf, glm::vec3 local) {
  return leaf.position + leaf.rotation * (local * leaf.scale);
}

glm::vec4 bounding_sphere(const Mesh& branches, const Mesh& leaf_card,
                          const std::vector<LeafPlacement>& leaves) {
  std::vector<glm::vec3> pts;
  pts.reserve(branches.vertices.size() + leaves.size() * leaf_card.vertices.size());
  for (const Vertex& v : branches.vertices) pts.push_back(v.position);
  for (const LeafPlacement& l : leaves)
    for (const Vertex& v : leaf_card.vertices) pts.push_back(leaf_to_model(l, v.position));
  if (pts.empty()) return glm::vec4(0.0f);

  auto farthest = [&](glm::dvec3 from) {
    size_t best = 0;
    double best_d = -1.0;
    for (size_t i = 0; i < pts.size(); ++i) {
      double d = glm::length(glm::dvec3(pts[i]) - from);
      if (d > best_d) best_d = d, best = i;
    }
    return glm::dvec3(pts[best]);
  };
  // Ritter (1990): a diameter guess from two far points, then grow toward outliers.
  glm::dvec3 a = farthest(glm::dvec3(pts[0]));
  glm::dvec3 b = farthest(a);
  glm::dvec3 c = (a + b) * 0.5;
  double r = glm::length(b - a) * 0.5;
  for (const glm::vec3& p : pts) {
    glm::dvec3 q(p);
    double d = glm::length(q - c);
    if (d > r) {
      double nr = (r + d) * 0.5;
      c += (q - c) * ((nr - r) / d);
      r = nr;
    }
  }
  // Exact radius about the float center, with a margin for float rounding by consumers.
  glm::vec3 cf(c);
  double rmax = 0.0;
  for (const glm::vec3& p : pts) rmax = std::max(rmax, glm::length(glm::dvec3(p) - glm::dvec3(cf)));
  return glm::vec4(cf, float(rmax * (1.0 + 1e-6) + 1e-6));
}

}  // namespace forest
