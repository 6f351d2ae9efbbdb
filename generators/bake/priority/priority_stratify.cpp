#include "generators/bake/priority/priority_stratify.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <tuple>

#include "generators/core/rng.h"

namespace forest {

namespace {
constexpr uint64_t kCellStream = 0x4345'4C4Cull;
}

std::vector<uint32_t> stratify_order(std::span<const uint32_t> order, std::span<const glm::vec3> centers,
                                     float cell, uint64_t seed) {
  std::vector<uint32_t> out(order.begin(), order.end());
  if (!(cell > 0.0f) || order.empty()) return out;
  // Cell of each leaf; cells numbered in order of their first leaf along `order`, so the
  // numbering (and the seeded offsets) depend on the inputs alone.
  std::map<std::tuple<int64_t, int64_t, int64_t>, uint32_t> cell_of_key;
  std::vector<uint32_t> cell_of(order.size()), count;
  std::vector<uint32_t> rank_in_cell(order.size());
  for (uint32_t i : order) {
    glm::vec3 c = centers[i] / cell;
    auto key = std::make_tuple(int64_t(std::floor(c.x)), int64_t(std::floor(c.y)), int64_t(std::floor(c.z)));
    auto [it, added] = cell_of_key.try_emplace(key, uint32_t(count.size()));
    if (added) count.push_back(0);
    cell_of[i] = it->second;
    rank_in_cell[i] = count[it->second]++;
  }
  // Position of each leaf in [0, 1): (k + u) / n.
  std::vector<double> key(order.size());
  for (uint32_t i : order) {
    double u = double(hash64(seed, kCellStream, cell_of[i]) >> 11) * 0x1.0p-53;
    key[i] = (double(rank_in_cell[i]) + u) / double(count[cell_of[i]]);
  }
  std::vector<uint32_t> position(order.size());
  for (size_t r = 0; r < order.size(); ++r) position[order[r]] = uint32_t(r);
  std::stable_sort(out.begin(), out.end(), [&](uint32_t a, uint32_t b) {
    if (key[a] != key[b]) return key[a] < key[b];
    return position[a] < position[b];
  });
  return out;
}

}  // namespace forest
