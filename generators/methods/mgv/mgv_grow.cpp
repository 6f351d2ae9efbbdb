#include "generators/methods/mgv/mgv_grow.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "generators/core/input_error.h"
#include "generators/core/rng.h"
#include "generators/methods/common/graph_dijkstra.h"
#include "generators/methods/common/graph_poisson.h"

namespace forest {

namespace {

constexpr float kPi = 3.14159265358979323846f;
const glm::vec3 kUp(0.0f, 1.0f, 0.0f);

glm::vec3 rotate_about(glm::vec3 v, glm::vec3 axis, float angle) {
  float c = std::cos(angle), s = std::sin(angle);
  return v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1.0f - c);
}

// Endpoints at least `spacing` apart, from candidates in random order (Poisson among nodes).
std::vector<uint32_t> poisson_pick(const YaoGraph& g, std::vector<uint32_t> cand, size_t count,
                                   float spacing, Rng& rng) {
  for (size_t i = cand.size(); i > 1; --i) {
    size_t j = std::min(size_t(rng.uniform() * double(i)), i - 1);
    std::swap(cand[i - 1], cand[j]);
  }
  std::vector<uint32_t> out;
  if (!(spacing > 0.0f)) {
    cand.resize(std::min(count, cand.size()));
    return cand;
  }
  std::unordered_map<uint64_t, std::vector<uint32_t>> cells;
  auto key = [](int x, int y, int z) {
    return (uint64_t(uint32_t(x + (1 << 20))) << 42) ^ (uint64_t(uint32_t(y + (1 << 20))) << 21) ^
           uint64_t(uint32_t(z + (1 << 20)));
  };
  const float s2 = spacing * spacing;
  for (uint32_t v : cand) {
    if (out.size() >= count) break;
    glm::vec3 p = g.positions[v];
    int c[3] = {int(std::floor(p.x / spacing)), int(std::floor(p.y / spacing)), int(std::floor(p.z / spacing))};
    bool ok = true;
    for (int dz = -1; dz <= 1 && ok; ++dz)
      for (int dy = -1; dy <= 1 && ok; ++dy)
        for (int dx = -1; dx <= 1 && ok; ++dx) {
          auto it = cells.find(key(c[0] + dx, c[1] + dy, c[2] + dz));
          if (it == cells.end()) continue;
          for (uint32_t w : it->second) {
            glm::vec3 d = g.positions[w] - p;
            if (glm::dot(d, d) < s2) {
              ok = false;
              break;
            }
          }
        }
    if (!ok) continue;
    cells[key(c[0], c[1], c[2])].push_back(v);
    out.push_back(v);
  }
  return out;
}

}  // namespace

MgvGraph build_mgv_graph(const MgvParams& P, uint64_t seed) {
  MgvGraph mg;
  Rng rng(seed, 11);
  Box box{glm::vec3(-0.5f * P.size.x, 0.0f, -0.5f * P.size.z),
          glm::vec3(0.5f * P.size.x, P.size.y, 0.5f * P.size.z)};
  double volume = double(P.size.x) * P.size.y * P.size.z;
  mg.spacing = spacing_for_count(volume, P.nodes);
  std::vector<glm::vec3> pts = poisson_disc([](glm::vec3) { return true; }, box, P.nodes,
                                            mg.spacing, rng, 20 * P.nodes + 1000);
  std::vector<glm::vec3> nodes{glm::vec3(0.0f)};
  nodes.reserve(pts.size() + 1);
  for (glm::vec3 p : pts)
    if (glm::length(p) >= mg.spacing) nodes.push_back(p);
  mg.graph = build_yao8(std::move(nodes), P.reach * mg.spacing);
  mg.root = 0;
  return mg;
}

glm::vec3 rotate_guide(glm::vec3 g, glm::vec3 edge, float alpha) {
  if (alpha == 0.0f) return g;
  glm::vec3 axis = glm::cross(kUp, g);
  if (glm::length(axis) < 1e-5f) axis = glm::cross(kUp, edge);
  if (glm::length(axis) < 1e-5f) return g;
  return glm::normalize(rotate_about(g, glm::normalize(axis), alpha));
}

TreeGraph grow_mgv(const MgvGraph& mg, const MgvParams& P, uint64_t seed, MgvStats* stats) {
  const YaoGraph& g = mg.graph;
  const size_t n = g.size();
  std::vector<glm::vec3> guide(n, glm::vec3(0.0f));
  std::vector<int32_t> tree_of(n, -1);     // graph node -> tree node
  std::vector<uint32_t> root_hops(n, 0);   // edges from the root along the tree
  std::vector<uint32_t> tree_nodes{mg.root};
  TreeGraph tree;
  tree.nodes.push_back(TreeNode{});
  tree.nodes[0].position = g.positions[mg.root];
  tree_of[mg.root] = 0;
  guide[mg.root] = kUp;
  MgvStats st;
  const float H = P.size.y;

  for (size_t it = 0; it < P.iterations.size(); ++it) {
    const MgvIteration& I = P.iterations[it];
    // Reset: every node outside the tree loses its guiding vector (weights are recomputed
    // from the guides, so they are reset with them).
    for (size_t v = 0; v < n; ++v)
      if (tree_of[v] < 0) guide[v] = glm::vec3(0.0f);
    auto alpha_of = [&](uint32_t v, uint32_t h, int32_t src) -> float {
      switch (I.rule) {
        case AlphaRule::Axis: {
          glm::vec3 p = g.positions[v] - g.positions[mg.root];
          float len = glm::length(p);
          float beta = len > 0.0f ? std::acos(std::clamp(p.y / len, -1.0f, 1.0f)) : 0.0f;
          return I.theta * std::sqrt(beta / kPi);
        }
        case AlphaRule::Height:
          return h <= I.h0 ? kPi * (1.0f - std::clamp(g.positions[v].y / H, 0.0f, 1.0f)) : I.alpha2;
        case AlphaRule::Piecewise:
          if (h > I.h0) return I.alpha2;
          if (!I.alpha1_random) return I.alpha1;
          {
            double u = double(hash64(seed, it, uint64_t(src)) >> 11) * 0x1.0p-53;
            return I.alpha1_lo + float(u) * (I.alpha1_hi - I.alpha1_lo);
          }
      }
      return 0.0f;
    };
    std::vector<uint32_t> sources;
    for (uint32_t v : tree_nodes)
      if (g.positions[v].y - g.positions[mg.root].y >= I.sources_above) sources.push_back(v);
    if (sources.empty()) {  // nothing high enough yet: the iteration adds nothing
      st.endpoints_per_iteration.push_back(0);
      continue;
    }
    ShortestPaths sp = dijkstra(
        g, sources,
        [&](uint32_t u, uint32_t e) {
          uint32_t v = g.targets[e];
          // A tree node below sources_above is not a way through (it is not a source).
          if (tree_of[v] >= 0 && g.positions[v].y - g.positions[mg.root].y < I.sources_above)
            return std::numeric_limits<float>::infinity();
          float len = g.lengths[e];
          glm::vec3 dir = (g.positions[v] - g.positions[u]) / len;
          return guided_weight(len, dir, guide[u]);
        },
        [&](uint32_t u, int32_t parent, const ShortestPaths& s) {
          if (tree_of[u] >= 0 || parent < 0) return;  // sources keep their vectors
          glm::vec3 edge = glm::normalize(g.positions[u] - g.positions[size_t(parent)]);
          guide[u] = rotate_guide(guide[size_t(parent)], edge, alpha_of(u, s.hops[u], s.source[u]));
        });

    // ---- endpoints ----
    std::vector<uint32_t> cand;
    auto policy_ok = [&](uint32_t v) {
      if (I.policy == EndpointPolicy::Any) return true;
      float src_y = g.positions[size_t(sp.source[v])].y;
      return I.policy == EndpointPolicy::Hanging ? g.positions[v].y < src_y : g.positions[v].y > src_y;
    };
    Rng rng(hash64(seed, it, 0x6d6776), 5);
    std::vector<uint32_t> chosen;
    if (I.select == EndpointSelect::Point) {
      double best = 1e300;
      int64_t at = -1;
      for (uint32_t v = 0; v < n; ++v) {
        if (!sp.reached(v) || tree_of[v] >= 0 || !policy_ok(v)) continue;
        double d = glm::length(g.positions[v] - I.point);
        if (d < best) {
          best = d;
          at = v;
        }
      }
      if (at >= 0) chosen.push_back(uint32_t(at));
    } else if (I.select == EndpointSelect::Volume) {
      for (uint32_t v = 0; v < n; ++v)
        if (sp.reached(v) && tree_of[v] < 0 && volume_contains(I.volume, g.positions[v]) && policy_ok(v))
          cand.push_back(v);
      Box vb = volume_bounds(I.volume);
      double vol = estimate_volume([&](glm::vec3 p) { return volume_contains(I.volume, p); }, vb, rng);
      // Endpoints as a Poisson-disc set: spacing for the count at a loose fill.
      float spacing = std::max(mg.spacing, spacing_for_count(vol, I.endpoints, 0.1));
      chosen = poisson_pick(g, std::move(cand), I.endpoints, spacing, rng);
    } else {
      for (uint32_t v = 0; v < n; ++v)
        if (sp.reached(v) && tree_of[v] < 0 && sp.hops[v] == I.hops && policy_ok(v)) cand.push_back(v);
      // The outermost fraction t by hop count from the root (ties: node index).
      std::sort(cand.begin(), cand.end(), [&](uint32_t a, uint32_t b) {
        uint32_t ha = root_hops[size_t(sp.source[a])] + sp.hops[a];
        uint32_t hb = root_hops[size_t(sp.source[b])] + sp.hops[b];
        return ha != hb ? ha > hb : a < b;
      });
      cand.resize(size_t(std::ceil(double(I.outer) * double(cand.size()))));
      chosen = poisson_pick(g, std::move(cand), I.endpoints, 0.0f, rng);
    }
    // ---- paths: endpoint -> first tree node, added top down ----
    std::vector<uint32_t> chain;
    for (uint32_t e : chosen) {
      chain.clear();
      for (uint32_t v = e; tree_of[v] < 0; v = uint32_t(sp.parent[v])) chain.push_back(v);
      for (size_t i = chain.size(); i-- > 0;) {
        uint32_t v = chain[i];
        uint32_t p = uint32_t(sp.parent[v]);
        TreeNode node;
        node.position = g.positions[v];
        node.parent = tree_of[p];
        node.order = uint32_t(it);
        tree_of[v] = int32_t(tree.nodes.size());
        root_hops[v] = root_hops[p] + 1;
        tree.nodes.push_back(node);
        tree_nodes.push_back(v);
      }
    }
    st.endpoints += chosen.size();
    st.endpoints_per_iteration.push_back(chosen.size());
  }
  if (stats) {
    st.guides = std::move(guide);
    st.tree_node = std::move(tree_of);
    *stats = std::move(st);
  }
  return tree;
}

}  // namespace forest
