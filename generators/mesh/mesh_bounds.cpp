// The leaf card, where a leaf puts it, and what is measured on meshes: the bounding sphere
// of a model and the open edges of a branch mesh.
#include "generators/mesh/mesher.h"

#include <algorithm>
#include <array>
#include <map>

namespace forest {

Mesh make_leaf_card(LeafShape shape) {
  const float w = leaf_card_aspect(shape);
  // Counter-clockwise seen from +Z: base left, base right, tip right, tip left.
  const glm::vec2 corners[4] = {{-0.5f * w, 0.0f}, {0.5f * w, 0.0f}, {0.5f * w, 1.0f}, {-0.5f * w, 1.0f}};
  Mesh card;
  for (const glm::vec2& p : corners) {
    Vertex v;
    v.position = glm::vec3(p, 0.0f);
    v.normal = glm::vec3(0.0f, 0.0f, 1.0f);
    v.uv = glm::vec2(0.5f + p.x / w, 1.0f - p.y);  // texture: leaf upright, tip at the top
    card.vertices.push_back(v);
  }
  card.indices = {0, 1, 2, 0, 2, 3};
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

size_t count_boundary_edges(const Mesh& mesh) {
  // Weld by exact position, then count undirected edges.
  std::map<std::array<float, 3>, uint32_t> ids;
  std::vector<uint32_t> weld(mesh.vertices.size());
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    const glm::vec3& p = mesh.vertices[i].position;
    weld[i] = ids.emplace(std::array<float, 3>{p.x, p.y, p.z}, uint32_t(ids.size())).first->second;
  }
  std::map<std::pair<uint32_t, uint32_t>, int> uses;
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      uint32_t a = weld[mesh.indices[t + size_t(k)]], b = weld[mesh.indices[t + size_t((k + 1) % 3)]];
      uses[{std::min(a, b), std::max(a, b)}]++;
    }
  size_t boundary = 0;
  for (const auto& [edge, n] : uses) boundary += n == 1;
  return boundary;
}

}  // namespace forest
