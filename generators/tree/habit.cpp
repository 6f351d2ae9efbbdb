#include "generators/tree/habit.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace forest {

namespace {

// Nodes bucketed in a uniform grid for nearest-node queries: a leaf carries no index of
// the node it grows on, so it is given to the nearest one (a twig node for leaves placed on
// twigs). About one node per occupied cell; rings of cells are searched outwards until the
// best distance found cannot be beaten by a farther ring.
struct NodeGrid {
  glm::vec3 lo{0.0f};
  float cell = 1.0f;
  glm::ivec3 dims{1};
  std::vector<uint32_t> start;  // per cell, into items (counting sort); size cells + 1
  std::vector<uint32_t> items;

  size_t index(glm::ivec3 c) const { return (size_t(c.z) * size_t(dims.y) + size_t(c.y)) * size_t(dims.x) + size_t(c.x); }
  glm::ivec3 cell_of(glm::vec3 p) const {
    glm::ivec3 c = glm::ivec3(glm::floor((p - lo) / cell));
    return glm::clamp(c, glm::ivec3(0), dims - 1);
  }
};

NodeGrid build_grid(const std::vector<TreeNode>& nodes) {
  NodeGrid g;
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const TreeNode& n : nodes) lo = glm::min(lo, n.position), hi = glm::max(hi, n.position);
  glm::vec3 size = hi - lo;
  float longest = std::max({size.x, size.y, size.z, 1e-6f});
  // Cell volume ≈ box volume / nodes, no axis cut finer than 1/128 of the longest side
  // (a flat or thin tree would otherwise get billions of empty cells).
  glm::vec3 padded = glm::max(size, glm::vec3(longest / 128.0f));
  g.cell = std::max(std::cbrt(padded.x * padded.y * padded.z / float(nodes.size())), longest / 128.0f);
  g.lo = lo;
  g.dims = glm::max(glm::ivec3(glm::floor(size / g.cell)) + 1, glm::ivec3(1));
  const size_t cells = size_t(g.dims.x) * size_t(g.dims.y) * size_t(g.dims.z);
  g.start.assign(cells + 1, 0);
  for (const TreeNode& n : nodes) ++g.start[g.index(g.cell_of(n.position)) + 1];
  for (size_t c = 0; c < cells; ++c) g.start[c + 1] += g.start[c];
  g.items.resize(nodes.size());
  std::vector<uint32_t> fill(g.start.begin(), g.start.end() - 1);
  for (uint32_t i = 0; i < nodes.size(); ++i) g.items[fill[g.index(g.cell_of(nodes[i].position))]++] = i;
  return g;
}

uint32_t nearest_node(const NodeGrid& g, const std::vector<TreeNode>& nodes, glm::vec3 p) {
  const glm::ivec3 c = g.cell_of(p);
  const int max_ring = std::max({g.dims.x, g.dims.y, g.dims.z});
  uint32_t best = 0;
  float best_d2 = std::numeric_limits<float>::max();
  for (int r = 0; r <= max_ring; ++r) {
    glm::ivec3 a = glm::max(c - r, glm::ivec3(0)), b = glm::min(c + r, g.dims - 1);
    for (int z = a.z; z <= b.z; ++z)
      for (int y = a.y; y <= b.y; ++y)
        for (int x = a.x; x <= b.x; ++x) {
          glm::ivec3 d = glm::abs(glm::ivec3(x, y, z) - c);
          if (std::max({d.x, d.y, d.z}) != r) continue;  // inner rings are done
          size_t k = g.index({x, y, z});
          for (uint32_t s = g.start[k]; s < g.start[k + 1]; ++s) {
            glm::vec3 v = nodes[g.items[s]].position - p;
            float d2 = glm::dot(v, v);
            if (d2 < best_d2 || (d2 == best_d2 && g.items[s] < best)) best_d2 = d2, best = g.items[s];
          }
        }
    // Every cell of ring r + 1 is at least r cells away from p, even for p outside the grid.
    float reach = float(r) * g.cell;
    if (best_d2 <= reach * reach) break;
  }
  return best;
}

// Subtree node counts (the graph's parent < own index makes one backward pass enough).
std::vector<uint32_t> subtree_sizes(const TreeGraph& graph) {
  std::vector<uint32_t> size(graph.nodes.size(), 1);
  for (size_t i = graph.nodes.size(); i-- > 1;) {
    int32_t p = graph.nodes[i].parent;
    if (p >= 0 && size_t(p) < i) size[size_t(p)] += size[i];
  }
  return size;
}

// `kids` ordered largest first: by radius, then by subtree size, then by index.
std::vector<uint32_t> ranked_children(const TreeGraph& graph, const std::vector<uint32_t>& kids,
                                      const std::vector<uint32_t>& sizes) {
  std::vector<uint32_t> out = kids;
  std::sort(out.begin(), out.end(), [&](uint32_t a, uint32_t b) {
    float ra = graph.nodes[a].radius, rb = graph.nodes[b].radius;
    if (ra != rb) return ra > rb;
    if (sizes[a] != sizes[b]) return sizes[a] > sizes[b];
    return a < b;
  });
  return out;
}

// The main stem (HabitMetrics): from the root, the largest child at every fork.
std::vector<uint32_t> stem_of(const TreeGraph& graph, const std::vector<std::vector<uint32_t>>& children,
                              const std::vector<uint32_t>& sizes) {
  std::vector<uint32_t> stem;
  for (uint32_t at = 0;;) {
    stem.push_back(at);
    if (children[at].empty()) break;
    at = ranked_children(graph, children[at], sizes)[0];
  }
  return stem;
}

// The stem's first codominant fork (an index into `stem`), or stem.size() when none.
size_t first_codominant_fork(const TreeGraph& graph, const std::vector<uint32_t>& stem,
                             const std::vector<std::vector<uint32_t>>& children, const std::vector<uint32_t>& sizes) {
  for (size_t k = 0; k < stem.size(); ++k) {
    const std::vector<uint32_t>& kids = children[stem[k]];
    if (kids.size() < 2) continue;
    std::vector<uint32_t> r = ranked_children(graph, kids, sizes);
    float first = graph.nodes[r[0]].radius, second = graph.nodes[r[1]].radius;
    if (first <= 0.0f) first = float(sizes[r[0]]), second = float(sizes[r[1]]);  // radii unknown
    if (second >= kCodominantRatio * first) return k;
  }
  return stem.size();
}

float fraction(float value, float height) { return height > 0.0f ? value / height : 0.0f; }

// Crown base above base_y: see HabitMetrics::crown_base.
float crown_base_height(const TreeGraph& graph, const std::vector<uint32_t>& stem,
                        const std::vector<std::vector<uint32_t>>& children, float base_y) {
  const size_t n = graph.nodes.size();
  std::vector<uint8_t> on_stem(n, 0);
  for (uint32_t s : stem) on_stem[s] = 1;
  float lowest = std::numeric_limits<float>::max();
  if (graph.leaves.empty()) {
    for (uint32_t s : stem)
      if (children[s].size() > 1) lowest = std::min(lowest, graph.nodes[s].position.y);
    return lowest == std::numeric_limits<float>::max() ? 0.0f : lowest - base_y;
  }
  // attach[i]: the stem node the branch holding node i leaves the stem from.
  std::vector<uint32_t> attach(n, 0);
  for (uint32_t i = 0; i < n; ++i) {
    int32_t p = graph.nodes[i].parent;
    attach[i] = on_stem[i] || p < 0 || uint32_t(p) >= i ? i : attach[uint32_t(p)];
  }
  NodeGrid grid = build_grid(graph.nodes);
  for (const LeafPlacement& leaf : graph.leaves)
    lowest = std::min(lowest, graph.nodes[attach[nearest_node(grid, graph.nodes, leaf.position)]].position.y);
  return lowest - base_y;
}

}  // namespace

glm::vec2 horizontal_extent(std::span<const glm::vec3> points) {
  if (points.empty()) return glm::vec2(0.0f);
  glm::vec2 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (glm::vec3 p : points) lo = glm::min(lo, glm::vec2(p.x, p.z)), hi = glm::max(hi, glm::vec2(p.x, p.z));
  return hi - lo;
}

std::vector<uint32_t> main_stem(const TreeGraph& graph) {
  if (graph.nodes.empty()) return {};
  return stem_of(graph, children_of(graph), subtree_sizes(graph));
}

HabitMetrics measure_habit(const TreeGraph& graph) {
  HabitMetrics m;
  m.nodes = uint32_t(graph.nodes.size());
  m.leaves = uint32_t(graph.leaves.size());
  if (graph.nodes.empty()) return m;
  m.base_y = graph.nodes[0].position.y;
  float top = m.base_y;
  for (const TreeNode& n : graph.nodes) top = std::max(top, n.position.y);
  m.height = top - m.base_y;

  std::vector<glm::vec3> crown;
  if (!graph.leaves.empty())
    for (const LeafPlacement& l : graph.leaves) crown.push_back(l.position);
  else
    for (const TreeNode& n : graph.nodes) crown.push_back(n.position);
  glm::vec2 extent = horizontal_extent(crown);
  m.crown_width_x = extent.x, m.crown_width_z = extent.y;
  m.crown_width = 0.5f * (extent.x + extent.y);
  m.crown_ratio = fraction(m.crown_width, m.height);

  if (!graph.leaves.empty()) {
    float lowest = std::numeric_limits<float>::max();
    for (const LeafPlacement& l : graph.leaves) lowest = std::min(lowest, l.position.y);
    m.lowest_leaf = fraction(lowest - m.base_y, m.height);
  }

  std::vector<std::vector<uint32_t>> children = children_of(graph);
  std::vector<uint32_t> sizes = subtree_sizes(graph);
  std::vector<uint32_t> stem = stem_of(graph, children, sizes);
  m.stem_nodes = uint32_t(stem.size());
  m.crown_base = crown_base_height(graph, stem, children, m.base_y);
  m.clear_bole = fraction(m.crown_base, m.height);

  const size_t fork = first_codominant_fork(graph, stem, children, sizes);
  m.codominant_fork = fork < stem.size();
  float reach = m.base_y;  // highest stem node up to the first codominant fork
  for (size_t k = 0; k < std::min(fork + 1, stem.size()); ++k) reach = std::max(reach, graph.nodes[stem[k]].position.y);
  m.trunk_height = (m.codominant_fork ? graph.nodes[stem[fork]].position.y : reach) - m.base_y;
  m.trunk_fraction = fraction(m.trunk_height, m.height);
  m.single_leader = m.height > 0.0f && reach - m.base_y >= kSingleLeaderFraction * m.height;
  return m;
}

}  // namespace forest
