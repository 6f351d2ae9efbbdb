#include "generators/methods/common/graph_skeleton.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "generators/core/toml_reader.h"
#include "generators/tree/pipe_model.h"

namespace forest {

namespace {

// Distance from p to segment [a, b].
float segment_distance(glm::vec3 p, glm::vec3 a, glm::vec3 b) {
  glm::vec3 ab = b - a;
  float len2 = glm::dot(ab, ab);
  float t = len2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / len2, 0.0f, 1.0f) : 0.0f;
  return glm::length(p - (a + t * ab));
}

// Iterative Douglas–Peucker over chain[first..last]; marks kept entries.
void douglas_peucker(const std::vector<glm::vec3>& pts, float tol, std::vector<char>& keep) {
  std::vector<std::pair<size_t, size_t>> stack{{0, pts.size() - 1}};
  while (!stack.empty()) {
    auto [a, b] = stack.back();
    stack.pop_back();
    if (b <= a + 1) continue;
    float worst = -1.0f;
    size_t at = a;
    for (size_t i = a + 1; i < b; ++i) {
      float d = segment_distance(pts[i], pts[a], pts[b]);
      if (d > worst) {
        worst = d;
        at = i;
      }
    }
    if (worst > tol) {
      keep[at] = 1;
      stack.push_back({a, at});
      stack.push_back({at, b});
    }
  }
}

}  // namespace

SkeletonStyle read_skeleton_style(const TomlTable& t, const SkeletonStyle& defaults) {
  SkeletonStyle s = defaults;
  s.smooth_iterations = int(t.integer("smooth", defaults.smooth_iterations, 0, 50));
  s.simplify = float(t.number("simplify", defaults.simplify, 0.0, 10.0));
  s.radius_model = t.choice("radius_model", defaults.radius_model == RadiusModel::Pipe ? "pipe" : "length",
                            {"length", "pipe"}) == "pipe"
                       ? RadiusModel::Pipe
                       : RadiusModel::Length;
  s.tip_radius = float(t.number("tip_radius", defaults.tip_radius, 1e-5, 1.0));
  s.trunk_radius = float(t.number("trunk_radius", defaults.trunk_radius, 1e-5, 10.0));
  if (s.trunk_radius < s.tip_radius) t.fail("trunk_radius", "must be >= tip_radius");
  s.zeta = float(t.number("zeta", defaults.zeta, 0.01, 3.0));
  s.pipe_exponent = float(t.number("pipe_exponent", defaults.pipe_exponent, 1.0, 4.0));
  return s;
}

void smooth_chains(TreeGraph& graph, int iterations) {
  const size_t n = graph.nodes.size();
  if (n < 3 || iterations <= 0) return;
  auto children = children_of(graph);
  std::vector<glm::vec3> next(n);
  for (int it = 0; it < iterations; ++it) {
    for (size_t i = 0; i < n; ++i) {
      const TreeNode& node = graph.nodes[i];
      next[i] = node.position;
      if (node.parent < 0 || children[i].size() != 1) continue;
      glm::vec3 mean = 0.5f * (graph.nodes[size_t(node.parent)].position +
                               graph.nodes[children[i][0]].position);
      next[i] = 0.5f * (node.position + mean);
    }
    for (size_t i = 0; i < n; ++i) graph.nodes[i].position = next[i];
  }
}

void simplify_chains(TreeGraph& graph, float tolerance) {
  const size_t n = graph.nodes.size();
  if (n < 3 || !(tolerance > 0.0f)) return;
  auto children = children_of(graph);
  std::vector<char> keep(n, 0);
  for (size_t i = 0; i < n; ++i)
    if (graph.nodes[i].parent < 0 || children[i].size() != 1) keep[i] = 1;
  // Every chain starts below a kept node: walk down through single-child nodes.
  std::vector<uint32_t> chain;
  std::vector<glm::vec3> pts;
  std::vector<char> chain_keep;
  for (size_t k = 0; k < n; ++k) {
    if (keep[k] != 1) continue;
    for (uint32_t c : children[k]) {
      chain.assign(1, uint32_t(k));
      uint32_t v = c;
      while (!keep[v]) {
        chain.push_back(v);
        v = children[v][0];
      }
      chain.push_back(v);
      if (chain.size() <= 2) continue;
      pts.resize(chain.size());
      for (size_t i = 0; i < chain.size(); ++i) pts[i] = graph.nodes[chain[i]].position;
      chain_keep.assign(chain.size(), 0);
      douglas_peucker(pts, tolerance, chain_keep);
      for (size_t i = 1; i + 1 < chain.size(); ++i)
        if (chain_keep[i]) keep[chain[i]] = 2;  // 2: kept interior (not re-walked as a start)
    }
  }
  // Re-index; a node's new parent is its nearest kept ancestor.
  std::vector<int32_t> remap(n, -1);
  std::vector<TreeNode> nodes;
  for (size_t i = 0; i < n; ++i) {
    if (!keep[i]) continue;
    TreeNode node = graph.nodes[i];
    int32_t p = node.parent;
    while (p >= 0 && !keep[size_t(p)]) p = graph.nodes[size_t(p)].parent;
    node.parent = p >= 0 ? remap[size_t(p)] : -1;
    remap[i] = int32_t(nodes.size());
    nodes.push_back(node);
  }
  graph.nodes = std::move(nodes);
}

void assign_length_radii(TreeGraph& graph, float tip_radius, float trunk_radius, float zeta) {
  const size_t n = graph.nodes.size();
  if (n == 0) return;
  std::vector<double> s(n, 0.0);  // longest path to a tip below
  for (size_t k = n; k-- > 1;) {
    int32_t p = graph.nodes[k].parent;
    if (p < 0) continue;
    double len = double(glm::length(graph.nodes[k].position - graph.nodes[size_t(p)].position));
    s[size_t(p)] = std::max(s[size_t(p)], s[k] + len);
  }
  double s_root = 0.0;
  for (double v : s) s_root = std::max(s_root, v);
  for (size_t i = 0; i < n; ++i) {
    double f = s_root > 0.0 ? std::pow(s[i] / s_root, double(zeta)) : 1.0;
    graph.nodes[i].radius = float(double(tip_radius) + double(trunk_radius - tip_radius) * f);
  }
}

size_t count_tips(const TreeGraph& graph) {
  std::vector<char> has_child(graph.nodes.size(), 0);
  for (const TreeNode& node : graph.nodes)
    if (node.parent >= 0) has_child[size_t(node.parent)] = 1;
  size_t tips = 0;
  for (size_t i = 1; i < has_child.size(); ++i) tips += has_child[i] ? 0 : 1;
  return tips;
}

TreeGraph finish_skeleton(TreeGraph graph, const SkeletonStyle& style) {
  smooth_chains(graph, style.smooth_iterations);
  simplify_chains(graph, style.simplify);
  if (style.radius_model == RadiusModel::Pipe)
    assign_pipe_radii(graph, style.tip_radius, style.pipe_exponent);
  else
    assign_length_radii(graph, style.tip_radius, style.trunk_radius, style.zeta);
  graph.leaves.clear();  // the shared foliage stage places them
  return graph;
}

}  // namespace forest
