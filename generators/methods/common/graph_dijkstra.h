// Multi-source Dijkstra on a Yao graph with lazily evaluated edge weights (Xu 2015 ch5.2.2):
// when a node is finalized, `on_finalize(u, parent)` runs (MGV sets u's guiding vector there),
// then u's out-edges are weighed by `weight(u, edge)` and relaxed. A weight is therefore
// only ever computed from a finalized node, which is exactly the thesis' lazy evaluation.
// The skeleton is read back from ONE run's parent pointers.
#pragma once
#include <cstdint>
#include <functional>
#include <limits>
#include <queue>
#include <span>
#include <utility>
#include <vector>

#include "generators/methods/common/graph_yao.h"

namespace forest {

struct ShortestPaths {
  std::vector<double> dist;      // +inf where unreachable
  std::vector<int32_t> parent;   // -1 for sources and unreachable nodes
  std::vector<uint32_t> hops;    // edges from the nearest source along the least-cost path
  std::vector<int32_t> source;   // the source node the path starts from (-1 unreachable)
  std::vector<uint32_t> order;   // nodes in finalization order (non-decreasing dist)
  bool reached(uint32_t v) const { return source[v] >= 0; }
};

template <class WeightFn, class FinalizeFn>
ShortestPaths dijkstra(const YaoGraph& g, std::span<const uint32_t> sources, WeightFn&& weight,
                       FinalizeFn&& on_finalize) {
  const size_t n = g.size();
  ShortestPaths sp;
  sp.dist.assign(n, std::numeric_limits<double>::infinity());
  sp.parent.assign(n, -1);
  sp.hops.assign(n, 0);
  sp.source.assign(n, -1);
  sp.order.reserve(n);
  std::vector<char> done(n, 0);
  using Item = std::pair<double, uint32_t>;  // ties broken by node index: deterministic
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  for (uint32_t s : sources) {
    if (s >= n || sp.dist[s] == 0.0) continue;
    sp.dist[s] = 0.0;
    sp.source[s] = int32_t(s);
    heap.push({0.0, s});
  }
  while (!heap.empty()) {
    auto [d, u] = heap.top();
    heap.pop();
    if (done[u] || d > sp.dist[u]) continue;
    done[u] = 1;
    sp.order.push_back(u);
    on_finalize(u, sp.parent[u], sp);
    for (uint32_t e = g.offsets[u]; e < g.offsets[u + 1]; ++e) {
      uint32_t v = g.targets[e];
      if (done[v]) continue;
      double nd = d + double(weight(u, e));
      if (nd < sp.dist[v]) {
        sp.dist[v] = nd;
        sp.parent[v] = int32_t(u);
        sp.hops[v] = sp.hops[u] + 1;
        sp.source[v] = sp.source[u];
        heap.push({nd, v});
      }
    }
  }
  return sp;
}

// Plain shortest paths with weight = edge length (MIG).
inline ShortestPaths dijkstra_lengths(const YaoGraph& g, std::span<const uint32_t> sources) {
  return dijkstra(
      g, sources, [&](uint32_t, uint32_t e) { return g.lengths[e]; },
      [](uint32_t, int32_t, const ShortestPaths&) {});
}

}  // namespace forest
