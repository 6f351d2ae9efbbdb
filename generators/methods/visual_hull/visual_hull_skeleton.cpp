#include "generators/methods/visual_hull/visual_hull_skeleton.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <queue>

#include "generators/methods/common/image_tree_util.h"
#include "generators/methods/visual_hull/voxel_thinning.h"

namespace forest {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

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


// Skeleton voxels after thinning with `marks` -> parent links of a tree rooted at `base`:
// breadth-first over 26-adjacent remaining voxels whose joining segment is inside the exact
// hull (or goes round a concave corner through one more hull voxel), then unmarked ends
// removed until every end is marked.
std::vector<int64_t> skeleton_tree(const ViewSet& set, const VoxelGrid& grid, const VoxelSolid& thin,
                                   const std::vector<uint8_t>& marked, size_t base) {
  Graph G{grid};
  std::vector<int64_t> parent(thin.occupied.size(), -2);  // -2: not in the tree
  parent[base] = -1;
  std::vector<size_t> order = {base};
  for (size_t q = 0; q < order.size(); ++q) {
    size_t i = order[q];
    glm::ivec3 c = G.cell(i);
    for (int k = 0; k < kNeighbours; ++k) {
      glm::ivec3 n = c + kOffsets.d[k];
      if (!thin.at(n)) continue;
      size_t j = thin.index(n);
      if (parent[j] != -2) continue;
      glm::dvec3 pc = grid.center(c.x, c.y, c.z), pn = grid.center(n.x, n.y, n.z);
      if (!segment_inside_hull(set, pc, pn)) {
        // The step cuts a concave corner of the exact hull: go round it through a hull voxel
        // next to both whose two segments are inside.
        bool joined = false;
        for (int k2 = 0; k2 < kNeighbours && !joined; ++k2) {
          glm::ivec3 w = c + kOffsets.d[k2];
          if (!G.occ(w) || glm::any(glm::greaterThan(glm::abs(w - n), glm::ivec3(1))) || w == n) continue;
          size_t mid = thin.index(w);
          glm::dvec3 pw = grid.center(w.x, w.y, w.z);
          if (parent[mid] != -2 || !segment_inside_hull(set, pc, pw) || !segment_inside_hull(set, pw, pn)) continue;
          parent[mid] = int64_t(i);
          order.push_back(mid);
          parent[j] = int64_t(mid);
          order.push_back(j);
          joined = true;
        }
        continue;
      }
      parent[j] = int64_t(i);
      order.push_back(j);
    }
  }
  std::vector<int> child_count(parent.size(), 0);
  for (size_t i : order)
    if (parent[i] >= 0) ++child_count[size_t(parent[i])];
  for (size_t q = order.size(); q-- > 1;) {  // children before parents
    size_t i = order[q];
    if (parent[i] != -2 && child_count[i] == 0 && !marked[i]) {
      for (int64_t p = int64_t(i); p >= 0 && size_t(p) != base && child_count[size_t(p)] == 0 && !marked[size_t(p)];) {
        int64_t up = parent[size_t(p)];
        parent[size_t(p)] = -2;
        --child_count[size_t(up)];
        p = up;
      }
    }
  }
  return parent;
}

}  // namespace

HullSkeleton hull_skeleton(const ViewSet& set, const VoxelGrid& grid, const SkeletonParams& params) {
  HullSkeleton out;
  Graph G{grid};
  const size_t n = grid.occupied.size();
  size_t occupied = 0;
  for (uint8_t o : grid.occupied) occupied += o;
  if (occupied == 0) return out;
  VoxelSolid solid{grid.dims, grid.occupied};
  const std::vector<double> dt = boundary_distance(solid);
  const size_t base = nearest_occupied(grid, set.base);
  // Marks must be reachable from the base inside the hull: hop distance from it.
  std::vector<double> reach = dijkstra(G, {base}, [](size_t) { return 1.0; }, nullptr);

  // Tips: interesting points of every view, lifted onto the hull along their rays.
  std::vector<uint8_t> marked(n, 0);
  marked[base] = 1;
  for (const View& v : set.views) {
    glm::dvec2 centroid(0.0);
    double area = 0.0;
    for (int j = 0; j < v.mask.height; ++j)
      for (int i = 0; i < v.mask.width; ++i)
        if (v.mask.inside(i, j)) centroid += glm::dvec2(i + 0.5, j + 0.5), area += 1.0;
    centroid /= std::max(area, 1.0);
    Projection foot = project(v.camera, set.base);
    std::optional<glm::dvec2> base_pixel;
    if (foot.in_front()) base_pixel = foot.pixel;
    for (const OutlineTip& tip : outline_tips(v.mask, params.tips, base_pixel, params.tips_per_view)) {
      glm::dvec2 q = tip.pixel;
      glm::dvec2 toward = glm::length(centroid - q) > 1e-9 ? glm::normalize(centroid - q) : glm::dvec2(0.0);
      for (int s = 0; s < 24; ++s) {  // step inward until the pixel ray meets the hull
        Ray r = pixel_ray(v.camera, q + toward * double(s));
        auto iv = hull_intervals(set, r.origin, r.direction, 0.0, 1e7);
        if (iv.empty()) continue;
        size_t t = nearest_occupied(grid, r.origin + r.direction * (0.5 * (iv.front().a + iv.front().b)));
        if (std::isfinite(reach[t])) {
          marked[t] = 1;
          ++out.lifted_tips;
        }
        break;
      }
    }
  }

  VoxelSolid thin = solid;
  auto thin_with_marks = [&] {
    thin = solid;
    std::vector<size_t> anchors;
    for (size_t i = 0; i < n; ++i)
      if (marked[i]) anchors.push_back(i);
    thin_to_anchors(thin, anchors, dt);
  };
  thin_with_marks();
  // Second pass: one more branching level where the hull is far from the skeleton.
  double dt_max = 0.0;
  for (size_t i = 0; i < n; ++i)
    if (grid.occupied[i]) dt_max = std::max(dt_max, dt[i] + 1.0);
  if (params.extra_branches > 0) {
    std::vector<size_t> sk;
    for (size_t i = 0; i < n; ++i)
      if (thin.occupied[i]) sk.push_back(i);
    std::vector<double> away = dijkstra(G, sk, [](size_t) { return 1.0; }, nullptr);
    for (int e = 0; e < params.extra_branches; ++e) {
      size_t best = n;
      double bd = 0.0;
      for (size_t i = 0; i < n; ++i)
        if (grid.occupied[i] && std::isfinite(reach[i]) && away[i] > bd) bd = away[i], best = i;
      if (best == n || bd < std::max(4.0, 0.5 * dt_max)) break;
      marked[best] = 1;
      ++out.second_pass;
      std::vector<double> from_new = dijkstra(G, {best}, [](size_t) { return 1.0; }, nullptr);
      for (size_t i = 0; i < n; ++i) away[i] = std::min(away[i], from_new[i]);
    }
    if (out.second_pass) thin_with_marks();
  }
  for (uint8_t m : marked) out.marks += m;

  std::vector<int64_t> parent = skeleton_tree(set, grid, thin, marked, base);
  std::vector<glm::dvec3> pos(n);
  for (size_t i = 0; i < n; ++i) {
    if (parent[i] == -2) {
      parent[i] = -1;
      continue;
    }
    glm::ivec3 c = G.cell(i);
    pos[i] = grid.center(c.x, c.y, c.z);
  }
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
