#include "generators/bake/priority/priority_density.h"

#include <algorithm>
#include <cmath>
#include <queue>

#include "generators/core/rng.h"

namespace forest {

std::vector<uint32_t> density_order(const MetaballField& field, const DensityOrderParams& params,
                                    uint64_t seed, size_t* greedy_removed) {
  const size_t n = field.centers.size();
  std::vector<uint32_t> order;
  if (n == 0) return order;
  const double r2 = double(field.radius) * double(field.radius);

  // Neighbours within the radius (self excluded) with their kernel value: the amount a
  // neighbour's density drops when this leaf is removed. Recomputed from the bucket grid on
  // demand rather than stored: memory O(n) even for very dense crowns.
  auto for_neighbours = [&](uint32_t i, auto&& fn) {
    const glm::vec3 p = field.centers[i];
    glm::ivec3 b = glm::ivec3(glm::floor((p - field.origin) / field.cell));
    b = glm::clamp(b, glm::ivec3(0), field.cells - 1);
    glm::ivec3 lo = glm::max(b - 1, glm::ivec3(0)), hi = glm::min(b + 1, field.cells - 1);
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) {
          size_t c = (size_t(z) * size_t(field.cells.y) + size_t(y)) * size_t(field.cells.x) + size_t(x);
          for (uint32_t k = field.cell_start[c]; k < field.cell_start[c + 1]; ++k) {
            uint32_t j = field.order[k];
            if (j == i) continue;
            glm::dvec3 d = glm::dvec3(field.centers[j]) - glm::dvec3(p);
            double d2 = glm::dot(d, d);
            if (d2 >= r2) continue;
            double t = 1.0 - d2 / r2;
            fn(j, t * t);
          }
        }
  };
  std::vector<double> density(n, 1.0);  // its own contribution
  for (size_t i = 0; i < n; ++i)
    for_neighbours(uint32_t(i), [&](uint32_t, double w) { density[i] += w; });

  double sum = 0.0, sum2 = 0.0;
  for (double f : density) sum += f, sum2 += f * f;
  std::vector<bool> removed(n, false);
  size_t remaining = n;
  // Max-heap on (density, lower index first) with lazy updates: densities only decrease, so
  // a popped entry whose stored value is stale is pushed back with the current one.
  using Entry = std::pair<double, uint32_t>;
  auto less = [](const Entry& a, const Entry& b) {
    return a.first < b.first || (a.first == b.first && a.second > b.second);
  };
  std::priority_queue<Entry, std::vector<Entry>, decltype(less)> heap(less);
  for (size_t i = 0; i < n; ++i) heap.push({density[i], uint32_t(i)});

  std::vector<uint32_t> removal;  // first removed first
  const size_t keep_random = size_t(std::ceil(double(params.random_below) * double(n)));
  // Each pop either removes a leaf or refreshes a stale entry, and an entry only goes stale
  // after a removal: the loop ends after at most n removals and n re-pushes per removal.
  while (remaining > keep_random && !heap.empty()) {
    const double mean = sum / double(remaining);
    const double var = std::max(0.0, sum2 / double(remaining) - mean * mean);
    if (std::sqrt(var) <= double(params.uniform_cv) * mean) break;
    auto [f, i] = heap.top();
    heap.pop();
    if (removed[i]) continue;
    if (f != density[i]) {
      heap.push({density[i], i});
      continue;
    }
    removed[i] = true;
    --remaining;
    sum -= density[i], sum2 -= density[i] * density[i];
    removal.push_back(i);
    for_neighbours(i, [&](uint32_t j, double w) {
      if (removed[j]) return;
      double before = density[j];
      density[j] -= w;
      sum += density[j] - before;
      sum2 += density[j] * density[j] - before * before;
    });
  }

  // Survivors of the greedy phase: random order (Fisher-Yates), then the removed ones,
  // last removed first.
  for (size_t i = 0; i < n; ++i)
    if (!removed[i]) order.push_back(uint32_t(i));
  Rng rng(seed, 0xDE45'1770ull);
  for (size_t i = order.size(); i > 1; --i) {
    size_t j = std::min(i - 1, size_t(rng.uniform() * double(i)));
    std::swap(order[i - 1], order[j]);
  }
  order.insert(order.end(), removal.rbegin(), removal.rend());
  if (greedy_removed) *greedy_removed = removal.size();
  return order;
}

}  // namespace forest
