#include "generators/methods/common/graph_yao.h"
#include "generators/core/limits.h"

#include <algorithm>
#include <cmath>
#include <thread>

#include "generators/core/input_error.h"

namespace forest {

namespace {


// Points bucketed into a uniform grid (counting sort: cell_start / items).
struct PointGrid {
  glm::vec3 lo{0.0f};
  float cell = 1.0f;
  int dims[3] = {1, 1, 1};
  std::vector<uint32_t> cell_start;  // size cells + 1
  std::vector<uint32_t> items;
  std::vector<glm::vec3> item_pos;   // positions in cell order: the search reads memory in order

  size_t index(int x, int y, int z) const { return (size_t(z) * dims[1] + y) * dims[0] + x; }
  int coord(float v, int a) const { return std::clamp(int((v - lo[a]) / cell), 0, dims[a] - 1); }
};

PointGrid make_grid(const std::vector<glm::vec3>& pts, float cell) {
  PointGrid g;
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (glm::vec3 p : pts) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  glm::vec3 ext = glm::max(hi - lo, glm::vec3(1e-6f));
  // Grow the cell until the grid is of sane size (few points per cell either way).
  double vol = double(ext.x) * ext.y * ext.z;
  cell = std::max(cell, float(std::cbrt(vol / double(kMaxYaoCells))) * 1.01f);
  g.lo = lo;
  g.cell = cell;
  for (int a = 0; a < 3; ++a) g.dims[a] = std::max(1, int(std::ceil(ext[a] / cell)) + 1);
  size_t cells = size_t(g.dims[0]) * g.dims[1] * g.dims[2];
  g.cell_start.assign(cells + 1, 0);
  std::vector<uint32_t> cell_of(pts.size());
  for (size_t i = 0; i < pts.size(); ++i) {
    cell_of[i] = uint32_t(g.index(g.coord(pts[i].x, 0), g.coord(pts[i].y, 1), g.coord(pts[i].z, 2)));
    ++g.cell_start[cell_of[i] + 1];
  }
  for (size_t c = 0; c < cells; ++c) g.cell_start[c + 1] += g.cell_start[c];
  g.items.resize(pts.size());
  std::vector<uint32_t> fill(g.cell_start.begin(), g.cell_start.end() - 1);
  for (size_t i = 0; i < pts.size(); ++i) g.items[fill[cell_of[i]]++] = uint32_t(i);
  g.item_pos.resize(pts.size());
  for (size_t k = 0; k < pts.size(); ++k) g.item_pos[k] = pts[g.items[k]];
  return g;
}

// Nearest node in each octant of node u (slots hold -1 where none within max_length).
void nearest_in_octants(const PointGrid& g, const std::vector<glm::vec3>& pts, uint32_t u,
                        float max_length, int32_t best[8]) {
  float best_d2[8];
  const float max2 = max_length * max_length;
  for (int k = 0; k < 8; ++k) {
    best[k] = -1;
    best_d2[k] = max2;
  }
  const glm::vec3 p = pts[u];
  const int cx = g.coord(p.x, 0), cy = g.coord(p.y, 1), cz = g.coord(p.z, 2);
  const int max_shell = std::max({g.dims[0], g.dims[1], g.dims[2]});
  auto visit = [&](int x, int y, int z) {
    // Skip a cell that cannot hold a nearer node for any octant it overlaps: per axis the
    // cell lies wholly on the + side, wholly on the − side, or straddles p.
    glm::vec3 lo = g.lo + glm::vec3(float(x), float(y), float(z)) * g.cell;
    glm::vec3 hi = lo + glm::vec3(g.cell);
    float gap2 = 0.0f;
    int neg[3], pos[3];
    for (int a = 0; a < 3; ++a) {
      float gap = lo[a] > p[a] ? lo[a] - p[a] : (hi[a] < p[a] ? p[a] - hi[a] : 0.0f);
      gap2 += gap * gap;
      pos[a] = hi[a] >= p[a];
      neg[a] = lo[a] < p[a];
    }
    bool useful = false;
    for (int k = 0; k < 8 && !useful; ++k) {
      bool fits = ((k & 1) ? pos[0] : neg[0]) && ((k & 2) ? pos[1] : neg[1]) && ((k & 4) ? pos[2] : neg[2]);
      if (fits && (best[k] < 0 ? gap2 <= max2 : gap2 <= best_d2[k])) useful = true;
    }
    if (!useful) return;
    size_t c = g.index(x, y, z);
    for (uint32_t k = g.cell_start[c]; k < g.cell_start[c + 1]; ++k) {
      uint32_t v = g.items[k];
      if (v == u) continue;
      glm::vec3 d = g.item_pos[k] - p;
      float d2 = glm::dot(d, d);
      if (d2 > max2) continue;
      int s = yao_sector(d);
      if (best[s] < 0 || d2 < best_d2[s] || (d2 == best_d2[s] && int32_t(v) < best[s])) {
        best_d2[s] = d2;
        best[s] = int32_t(v);
      }
    }
  };
  for (int s = 0; s <= max_shell; ++s) {
    // Cells at Chebyshev distance exactly s from the node's cell.
    for (int z = cz - s; z <= cz + s; ++z) {
      if (z < 0 || z >= g.dims[2]) continue;
      for (int y = cy - s; y <= cy + s; ++y) {
        if (y < 0 || y >= g.dims[1]) continue;
        bool yz_edge = (z == cz - s || z == cz + s || y == cy - s || y == cy + s);
        if (yz_edge) {
          for (int x = std::max(0, cx - s); x <= std::min(g.dims[0] - 1, cx + s); ++x) visit(x, y, z);
        } else {
          if (cx - s >= 0) visit(cx - s, y, z);
          if (s > 0 && cx + s < g.dims[0]) visit(cx + s, y, z);
        }
      }
    }
    // Every point not yet visited is at least s·cell away.
    float reach = float(s) * g.cell;
    if (reach >= max_length) break;
    bool done = true;
    for (int k = 0; k < 8 && done; ++k)
      if (best[k] < 0 || best_d2[k] > reach * reach) done = false;
    if (done) break;
  }
}

}  // namespace

YaoGraph build_yao8(std::vector<glm::vec3> positions, float max_length) {
  YaoGraph graph;
  graph.positions = std::move(positions);
  const std::vector<glm::vec3>& pts = graph.positions;
  const size_t n = pts.size();
  graph.offsets.assign(n + 1, 0);
  if (n == 0) return graph;
  if (!(max_length > 0.0f) || !std::isfinite(max_length))
    throw InputError("Yao graph: edge length limit must be positive and finite");
  PointGrid grid = make_grid(pts, max_length / 2.0f);
  std::vector<int32_t> slots(n * 8);
  auto work = [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) {  // in cell order, for locality
      uint32_t u = grid.items[k];
      nearest_in_octants(grid, pts, u, max_length, &slots[size_t(u) * 8]);
    }
  };
  if (n > 20000) {
    std::thread other(work, n / 2, n);
    work(0, n / 2);
    other.join();
  } else {
    work(0, n);
  }
  for (size_t u = 0; u < n; ++u) {
    uint32_t deg = 0;
    for (int k = 0; k < 8; ++k) deg += slots[u * 8 + k] >= 0 ? 1u : 0u;
    graph.offsets[u + 1] = graph.offsets[u] + deg;
  }
  graph.targets.resize(graph.offsets[n]);
  graph.lengths.resize(graph.offsets[n]);
  for (size_t u = 0; u < n; ++u) {
    uint32_t e = graph.offsets[u];
    for (int k = 0; k < 8; ++k) {
      int32_t v = slots[u * 8 + k];
      if (v < 0) continue;
      graph.targets[e] = uint32_t(v);
      graph.lengths[e] = glm::length(pts[size_t(v)] - pts[u]);
      ++e;
    }
  }
  return graph;
}

}  // namespace forest
