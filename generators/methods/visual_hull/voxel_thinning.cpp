#include "generators/methods/visual_hull/voxel_thinning.h"

#include <cmath>
#include <limits>
#include <queue>

namespace forest {

namespace {

// 3x3x3 neighbourhood index of offset (dx, dy, dz) in {-1, 0, 1}^3; 13 is the centre.
constexpr int nb(int dx, int dy, int dz) { return (dz + 1) * 9 + (dy + 1) * 3 + (dx + 1); }

// Components of the cells of `set` (a 27-bit mask) under the adjacency `adjacent`, counting
// only components that contain a cell of `must_touch` (0 = any).
template <class Adjacent>
int components(uint32_t set, uint32_t must_touch, Adjacent adjacent) {
  int count = 0;
  uint32_t seen = 0;
  for (int s = 0; s < 27; ++s) {
    if (!(set >> s & 1u) || (seen >> s & 1u)) continue;
    uint32_t comp = 1u << s;
    int stack[27], top = 0;
    stack[top++] = s;
    seen |= 1u << s;
    while (top) {
      int a = stack[--top];
      for (int b = 0; b < 27; ++b)
        if ((set >> b & 1u) && !(seen >> b & 1u) && adjacent(a, b)) {
          seen |= 1u << b;
          comp |= 1u << b;
          stack[top++] = b;
        }
    }
    if (must_touch == 0 || (comp & must_touch)) ++count;
  }
  return count;
}

glm::ivec3 offset(int k) { return {k % 3 - 1, (k / 3) % 3 - 1, k / 9 - 1}; }

}  // namespace

std::vector<double> boundary_distance(const VoxelSolid& s) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> dist(s.occupied.size(), inf);
  using Item = std::pair<double, size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  for (size_t i = 0; i < s.occupied.size(); ++i) {
    if (!s.occupied[i]) continue;
    glm::ivec3 c = s.cell(i);
    for (int k = 0; k < 27; ++k)
      if (k != 13 && !s.at(c + offset(k))) {
        dist[i] = 0.0;
        q.push({0.0, i});
        break;
      }
  }
  while (!q.empty()) {
    auto [d, i] = q.top();
    q.pop();
    if (d > dist[i]) continue;
    glm::ivec3 c = s.cell(i);
    for (int k = 0; k < 27; ++k) {
      glm::ivec3 o = offset(k), n = c + o;
      if (k == 13 || !s.at(n)) continue;
      size_t j = s.index(n);
      double nd = d + std::sqrt(double(o.x * o.x + o.y * o.y + o.z * o.z));
      if (nd < dist[j]) dist[j] = nd, q.push({nd, j});
    }
  }
  return dist;
}

bool is_simple_voxel(const VoxelSolid& s, glm::ivec3 c) {
  uint32_t fg = 0, bg18 = 0;
  for (int k = 0; k < 27; ++k) {
    if (k == 13) continue;
    glm::ivec3 o = offset(k);
    bool in = s.at(c + o);
    int nonzero = (o.x != 0) + (o.y != 0) + (o.z != 0);
    if (in) fg |= 1u << k;
    else if (nonzero <= 2) bg18 |= 1u << k;
  }
  auto adj26 = [](int a, int b) {
    glm::ivec3 d = offset(a) - offset(b);
    return std::abs(d.x) <= 1 && std::abs(d.y) <= 1 && std::abs(d.z) <= 1;
  };
  auto adj6 = [](int a, int b) {
    glm::ivec3 d = offset(a) - offset(b);
    return std::abs(d.x) + std::abs(d.y) + std::abs(d.z) == 1;
  };
  const uint32_t faces = 1u << nb(1, 0, 0) | 1u << nb(-1, 0, 0) | 1u << nb(0, 1, 0) | 1u << nb(0, -1, 0) |
                         1u << nb(0, 0, 1) | 1u << nb(0, 0, -1);
  return components(fg, 0, adj26) == 1 && components(bg18, faces, adj6) == 1;
}

void thin_to_anchors(VoxelSolid& s, const std::vector<size_t>& anchors, const std::vector<double>& distance) {
  std::vector<uint8_t> anchor(s.occupied.size(), 0), queued(s.occupied.size(), 0);
  for (size_t a : anchors) anchor[a] = 1;
  // Ties broken by index so the result is deterministic.
  using Item = std::pair<double, size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  for (size_t i = 0; i < s.occupied.size(); ++i)
    if (s.occupied[i] && distance[i] == 0.0) q.push({0.0, i}), queued[i] = 1;
  while (!q.empty()) {
    size_t i = q.top().second;
    q.pop();
    queued[i] = 0;
    if (!s.occupied[i] || anchor[i]) continue;
    glm::ivec3 c = s.cell(i);
    if (!is_simple_voxel(s, c)) continue;  // offered again when a neighbour goes
    s.occupied[i] = 0;
    for (int k = 0; k < 27; ++k) {
      glm::ivec3 n = c + offset(k);
      if (k == 13 || !s.at(n)) continue;
      size_t j = s.index(n);
      if (!queued[j] && !anchor[j]) queued[j] = 1, q.push({distance[j], j});
    }
  }
}

}  // namespace forest
