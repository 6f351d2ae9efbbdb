#include "generators/methods/visual_hull_skeleton.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include "generators/methods/image_tree_util.h"

namespace forest {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();

double cross(glm::dvec2 o, glm::dvec2 a, glm::dvec2 b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// Andrew's monotone chain; counter-clockwise in (u, v), no collinear points.
std::vector<glm::dvec2> convex_hull(std::vector<glm::dvec2> p) {
  std::sort(p.begin(), p.end(), [](glm::dvec2 a, glm::dvec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  std::vector<glm::dvec2> h(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

double segment_distance(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
  glm::dvec2 ab = b - a;
  double t = std::clamp(glm::dot(p - a, ab) / std::max(glm::dot(ab, ab), 1e-300), 0.0, 1.0);
  return glm::length(p - (a + t * ab));
}

const int kNeighbours = 26;
struct Offsets {
  glm::ivec3 d[kNeighbours];
  double len[kNeighbours];
  Offsets() {
    int k = 0;
    for (int z = -1; z <= 1; ++z)
      for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x)
          if (x || y || z) {
            d[k] = {x, y, z};
            len[k++] = std::sqrt(double(x * x + y * y + z * z));
          }
  }
};
const Offsets kOffsets;

struct Graph {
  const VoxelGrid& g;
  bool valid(glm::ivec3 c) const {
    return c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x < g.dims.x && c.y < g.dims.y && c.z < g.dims.z;
  }
  glm::ivec3 cell(size_t i) const {
    int x = int(i % size_t(g.dims.x)), y = int((i / size_t(g.dims.x)) % size_t(g.dims.y));
    return {x, y, int(i / (size_t(g.dims.x) * size_t(g.dims.y)))};
  }
  bool occ(glm::ivec3 c) const { return valid(c) && g.occupied[g.index(c.x, c.y, c.z)]; }
};

// Multi-source Dijkstra over occupied voxels (26-neighbours, Euclidean steps times the
// optional per-target weight). Returns distances; pred receives the predecessor of each cell.
template <class StepCost>
std::vector<double> dijkstra(const Graph& G, const std::vector<size_t>& sources, StepCost cost,
                             std::vector<int64_t>* pred) {
  std::vector<double> dist(G.g.occupied.size(), kInf);
  if (pred) pred->assign(dist.size(), -1);
  using Item = std::pair<double, size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  for (size_t s : sources) {
    dist[s] = 0.0;
    q.push({0.0, s});
  }
  while (!q.empty()) {
    auto [d, i] = q.top();
    q.pop();
    if (d > dist[i]) continue;
    glm::ivec3 c = G.cell(i);
    for (int k = 0; k < kNeighbours; ++k) {
      glm::ivec3 n = c + kOffsets.d[k];
      if (!G.occ(n)) continue;
      size_t j = G.g.index(n.x, n.y, n.z);
      double nd = d + kOffsets.len[k] * cost(j);
      if (nd < dist[j]) {
        dist[j] = nd;
        if (pred) (*pred)[j] = int64_t(i);
        q.push({nd, j});
      }
    }
  }
  return dist;
}

size_t nearest_occupied(const VoxelGrid& g, glm::dvec3 p) {
  size_t best = 0;
  double bd = kInf;
  for (size_t i = 0; i < g.occupied.size(); ++i) {
    if (!g.occupied[i]) continue;
    glm::ivec3 c = Graph{g}.cell(i);
    double d = glm::length(g.center(c.x, c.y, c.z) - p);
    if (d < bd) bd = d, best = i;
  }
  return best;
}

}  // namespace

std::vector<glm::dvec2> interesting_points(const Mask& m, int count, double min_separation) {
  std::vector<glm::dvec2> boundary;
  glm::dvec2 centroid(0.0);
  double area = 0.0;
  for (int j = 0; j < m.height; ++j)
    for (int i = 0; i < m.width; ++i) {
      if (!m.inside(i, j)) continue;
      centroid += glm::dvec2(i + 0.5, j + 0.5);
      area += 1.0;
      if (!m.inside(i - 1, j) || !m.inside(i + 1, j) || !m.inside(i, j - 1) || !m.inside(i, j + 1))
        boundary.push_back({i + 0.5, j + 0.5});
    }
  std::vector<glm::dvec2> hull = convex_hull(boundary);
  const size_t h = hull.size();
  if (h < 3) return hull;
  double perimeter = 0.0;
  for (size_t k = 0; k < h; ++k) perimeter += glm::length(hull[(k + 1) % h] - hull[k]);
  // Pocket depth of each hull edge: the outline pixels nearest to that edge, farthest away.
  std::vector<double> depth(h, 0.0);
  for (glm::dvec2 p : boundary) {
    size_t best = 0;
    double bd = kInf;
    for (size_t k = 0; k < h; ++k) {
      double d = segment_distance(p, hull[k], hull[(k + 1) % h]);
      if (d < bd) bd = d, best = k;
    }
    depth[best] = std::max(depth[best], bd);
  }
  auto edge_interest = [&](size_t k) {
    return glm::length(hull[(k + 1) % h] - hull[k]) / perimeter + depth[k] / std::sqrt(area);
  };
  std::vector<std::pair<double, size_t>> ranked;
  for (size_t k = 0; k < h; ++k) {
    glm::dvec2 a = hull[(k + h - 1) % h] - hull[k], b = hull[(k + 1) % h] - hull[k];
    double angle = std::acos(std::clamp(glm::dot(a, b) / (glm::length(a) * glm::length(b)), -1.0, 1.0));
    double sharp = (kPi - angle) / kPi;
    double score = sharp + std::max(edge_interest((k + h - 1) % h), edge_interest(k));
    // Tips point away from the trunk: favour the upper and outer part of the silhouette.
    score += 0.1 * glm::length(hull[k] - centroid / area) / std::sqrt(area);
    ranked.push_back({-score, k});
  }
  std::sort(ranked.begin(), ranked.end());
  std::vector<glm::dvec2> out;
  double sep = min_separation * std::hypot(double(m.width), double(m.height));
  for (auto [s, k] : ranked) {
    if (int(out.size()) >= count) break;
    bool far = true;
    for (glm::dvec2 q : out) far = far && glm::length(q - hull[k]) >= sep;
    if (far) out.push_back(hull[k]);
  }
  return out;
}

HullSkeleton hull_skeleton(const ViewSet& set, const VoxelGrid& grid, const SkeletonParams& params) {
  HullSkeleton out;
  Graph G{grid};
  const size_t n = grid.occupied.size();
  size_t occupied = 0;
  for (uint8_t o : grid.occupied) occupied += o;
  if (occupied == 0) return out;

  // Distance to the hull boundary (cells), for the medial penalty.
  std::vector<size_t> rim;
  for (size_t i = 0; i < n; ++i) {
    if (!grid.occupied[i]) continue;
    glm::ivec3 c = G.cell(i);
    for (int k = 0; k < kNeighbours; ++k)
      if (!G.occ(c + kOffsets.d[k])) {
        rim.push_back(i);
        break;
      }
  }
  std::vector<double> dt = dijkstra(G, rim, [](size_t) { return 1.0; }, nullptr);
  double dt_max = 0.0;
  for (size_t i = 0; i < n; ++i)
    if (grid.occupied[i]) dt_max = std::max(dt_max, dt[i] + 1.0);
  // TEASAR's penalty: large near the boundary, ~1 on the medial axis.
  auto penalty = [&](size_t j) { return 1.0 + 5000.0 * std::pow(1.0 - (dt[j] + 1.0) / dt_max, 16.0); };

  const size_t base = nearest_occupied(grid, set.base);
  std::vector<int64_t> pred;
  std::vector<double> cost = dijkstra(G, {base}, penalty, &pred);

  // Tips: interesting points of every view, lifted onto the hull along their rays.
  std::vector<size_t> tips;
  for (const View& v : set.views) {
    glm::dvec2 centroid(0.0);
    double area = 0.0;
    for (int j = 0; j < v.mask.height; ++j)
      for (int i = 0; i < v.mask.width; ++i)
        if (v.mask.inside(i, j)) centroid += glm::dvec2(i + 0.5, j + 0.5), area += 1.0;
    centroid /= std::max(area, 1.0);
    for (glm::dvec2 q : interesting_points(v.mask, params.tips_per_view, params.min_tip_separation)) {
      glm::dvec2 toward = glm::length(centroid - q) > 1e-9 ? glm::normalize(centroid - q) : glm::dvec2(0.0);
      for (int s = 0; s < 24; ++s) {  // step inward until the pixel ray meets the hull
        Ray r = pixel_ray(v.camera, q + toward * double(s));
        auto iv = hull_intervals(set, r.origin, r.direction, 0.0, 1e7);
        if (iv.empty()) continue;
        size_t t = nearest_occupied(grid, r.origin + r.direction * (0.5 * (iv.front().a + iv.front().b)));
        if (std::isfinite(cost[t])) {
          tips.push_back(t);
          ++out.lifted_tips;
        }
        break;
      }
    }
  }
  std::sort(tips.begin(), tips.end());
  tips.erase(std::unique(tips.begin(), tips.end()), tips.end());

  std::vector<uint8_t> on_skeleton(n, 0), marked(n, 0);
  on_skeleton[base] = marked[base] = 1;
  auto add_path = [&](size_t t) {
    marked[t] = 1;
    for (int64_t i = int64_t(t); i >= 0 && !on_skeleton[size_t(i)]; i = pred[size_t(i)]) on_skeleton[size_t(i)] = 1;
  };
  for (size_t t : tips) add_path(t);
  // Second pass: one more branching level where the hull is far from the skeleton.
  for (int e = 0; e < params.extra_branches; ++e) {
    std::vector<size_t> sk;
    for (size_t i = 0; i < n; ++i)
      if (on_skeleton[i]) sk.push_back(i);
    std::vector<double> away = dijkstra(G, sk, [](size_t) { return 1.0; }, nullptr);
    size_t best = n;
    double bd = 0.0;
    for (size_t i = 0; i < n; ++i)
      if (grid.occupied[i] && std::isfinite(away[i]) && std::isfinite(cost[i]) && away[i] > bd) bd = away[i], best = i;
    // Stop when every hull cell is within a few cells (and its own depth) of the skeleton.
    if (best == n || bd < std::max(4.0, 0.5 * dt_max)) break;
    add_path(best);
  }

  // Voxel paths -> graph, checked segment by segment against the exact hull.
  std::vector<glm::dvec3> pos(n);
  std::vector<int64_t> parent(n, -1);
  for (size_t i = 0; i < n; ++i) {
    if (!on_skeleton[i]) continue;
    glm::ivec3 c = G.cell(i);
    pos[i] = grid.center(c.x, c.y, c.z);
    if (i != base) parent[i] = pred[i];
  }
  for (size_t i = 0; i < n; ++i)
    if (on_skeleton[i] && i != base && !segment_inside_hull(set, pos[size_t(parent[i])], pos[i])) parent[i] = -1;
  std::vector<int64_t> map;
  TreeGraph full = rooted_tree(pos, parent, base, &map);
  std::vector<uint8_t> full_marked(full.nodes.size(), 0);
  for (size_t i = 0; i < n; ++i)
    if (map[i] >= 0 && marked[i]) full_marked[size_t(map[i])] = 1;

  // Simplify chains: drop a node when the shortcut from its kept ancestor to its only child
  // stays inside the hull and spans at most 3 cells.
  auto children = children_of(full);
  const size_t m = full.nodes.size();
  std::vector<int64_t> eff(m, -1), keep(m, 1);
  std::vector<glm::dvec3> fpos(m);
  for (size_t i = 0; i < m; ++i) fpos[i] = glm::dvec3(full.nodes[i].position);
  for (size_t i = 1; i < m; ++i) {
    size_t p = size_t(full.nodes[i].parent);
    eff[i] = keep[p] ? int64_t(p) : eff[p];
    if (children[i].size() == 1 && !full_marked[i]) {
      glm::dvec3 a = fpos[size_t(eff[i])], c = fpos[children[i][0]];
      if (glm::length(c - a) <= 3.0 * grid.cell + 1e-9 && segment_inside_hull(set, a, c)) keep[i] = 0;
    }
  }
  std::vector<int64_t> sparent(m, -1);
  for (size_t i = 1; i < m; ++i)
    if (keep[i]) sparent[i] = eff[i];
  std::vector<int64_t> smap;
  out.graph = rooted_tree(fpos, sparent, 0, &smap);
  for (size_t i = 0; i < m; ++i)
    if (full_marked[i] && smap[i] >= 0) out.marked.push_back(uint32_t(smap[i]));
  std::sort(out.marked.begin(), out.marked.end());
  assign_branch_orders(out.graph);
  return out;
}

}  // namespace forest
