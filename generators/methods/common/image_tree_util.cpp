#include "generators/methods/common/image_tree_util.h"

#include <algorithm>
#include <cmath>

namespace forest {

TreeGraph rooted_tree(const std::vector<glm::dvec3>& positions, const std::vector<int64_t>& parent,
                      size_t root, std::vector<int64_t>* old_to_new) {
  const size_t n = positions.size();
  std::vector<std::vector<uint32_t>> children(n);
  for (size_t i = 0; i < n; ++i)
    if (parent[i] >= 0 && size_t(parent[i]) < n && i != root) children[size_t(parent[i])].push_back(uint32_t(i));
  std::vector<int64_t> map(n, -1);
  TreeGraph g;
  std::vector<size_t> queue = {root};
  map[root] = 0;
  g.nodes.push_back({glm::vec3(positions[root]), 0.0f, -1, 0});
  for (size_t q = 0; q < queue.size(); ++q) {
    size_t i = queue[q];
    for (uint32_t c : children[i]) {
      if (map[c] >= 0) continue;  // visited (cannot happen for a forest, guards bad input)
      map[c] = int64_t(g.nodes.size());
      g.nodes.push_back({glm::vec3(positions[c]), 0.0f, int32_t(map[i]), 0});
      queue.push_back(c);
    }
  }
  if (old_to_new) *old_to_new = std::move(map);
  return g;
}

void assign_branch_orders(TreeGraph& g) {
  const size_t n = g.nodes.size();
  auto children = children_of(g);
  std::vector<uint32_t> tips(n, 0);
  for (size_t k = n; k-- > 0;) {
    if (children[k].empty()) tips[k] = 1;
    if (g.nodes[k].parent >= 0) tips[size_t(g.nodes[k].parent)] += tips[k];
  }
  if (n) g.nodes[0].order = 0;
  for (size_t i = 0; i < n; ++i) {
    const auto& c = children[i];
    if (c.empty()) continue;
    uint32_t main = *std::max_element(c.begin(), c.end(), [&](uint32_t a, uint32_t b) { return tips[a] < tips[b]; });
    for (uint32_t k : c) g.nodes[k].order = g.nodes[i].order + (k == main ? 0u : 1u);
  }
}

void drop_leaves_outside_masks(TreeGraph& graph, const ViewSet& set) {
  std::vector<LeafPlacement> kept;
  for (const LeafPlacement& l : graph.leaves) {
    bool ok = true;
    for (const View& v : set.views) {
      Projection p = project(v.camera, glm::dvec3(l.position));
      if (!p.in_front() || !(p.pixel.x >= 0.0 && p.pixel.y >= 0.0) ||
          !v.mask.inside(int(std::floor(p.pixel.x)), int(std::floor(p.pixel.y)))) {
        ok = false;
        break;
      }
    }
    if (ok) kept.push_back(l);
  }
  graph.leaves = std::move(kept);
}

bool is_rooted_tree(const TreeGraph& g) {
  if (g.nodes.empty() || g.nodes[0].parent != -1) return false;
  for (size_t i = 1; i < g.nodes.size(); ++i)
    if (g.nodes[i].parent < 0 || size_t(g.nodes[i].parent) >= i) return false;
  return true;
}

}  // namespace forest
