#include "generators/methods/visual_hull/visual_hull_growth.h"

#include <algorithm>
#include <cmath>

#include "generators/methods/common/image_tree_util.h"
#include "generators/mesh/frames.h"

namespace forest {

namespace {

glm::dvec3 perpendicular(glm::dvec3 a) { return glm::dvec3(any_perpendicular(glm::vec3(a))); }

// Direction at `angle` from `axis`, rolled by `roll` about it (radians).
glm::dvec3 deflect(glm::dvec3 axis, double angle, double roll) {
  glm::dvec3 a = glm::normalize(axis), p = perpendicular(a), q = glm::cross(a, p);
  glm::dvec3 side = p * std::cos(roll) + q * std::sin(roll);
  return glm::normalize(a * std::cos(angle) + side * std::sin(angle));
}

glm::ivec3 cell_of(const VoxelGrid& g, glm::dvec3 p) {
  return glm::ivec3(glm::floor((p - g.origin) / g.cell));
}

bool valid(const VoxelGrid& g, glm::ivec3 c) {
  return c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x < g.dims.x && c.y < g.dims.y && c.z < g.dims.z;
}

}  // namespace

GrowthState start_growth(const HullSkeleton& skeleton, const GrowthParams& params) {
  GrowthState s;
  const TreeGraph& g = skeleton.graph;
  auto children = children_of(g);
  for (const TreeNode& n : g.nodes) {
    s.pos.push_back(glm::dvec3(n.position));
    s.parent.push_back(n.parent);
    s.order.push_back(n.order);
  }
  s.alive.assign(s.pos.size(), 1);
  s.fixed.assign(s.pos.size(), 1);
  const double angle = glm::radians(params.branch_angle_deg), roll = glm::radians(params.phyllotaxis_deg);
  for (size_t i = 1; i < g.nodes.size(); ++i) {
    glm::dvec3 dir = s.pos[i] - s.pos[size_t(s.parent[i])];
    if (glm::length(dir) < 1e-12) dir = {0, 1, 0};
    dir = glm::normalize(dir);
    Bud b;
    b.node = uint32_t(i);
    b.length = params.internode;
    if (children[i].empty()) {  // apical bud at a skeleton tip
      b.heading = dir;
      b.order = s.order[i];
    } else {  // lateral bud on the skeleton
      b.heading = deflect(dir, angle, roll * double(i));
      b.order = s.order[i] + 1;
    }
    if (int(b.order) <= params.max_order) s.buds.push_back(b);
  }
  s.flow.assign(s.pos.size(), 0.0);
  return s;
}

YearReport grow_year(GrowthState& s, const ViewSet& set, const VoxelGrid& grid,
                     const GrowthParams& params, Rng& rng) {
  YearReport r;
  const size_t n = s.pos.size();

  // 1. Light from shadow propagation (pyramid of depth 4 below every live bud).
  std::vector<float> shadow(grid.occupied.size(), 0.0f);
  for (const Bud& b : s.buds) {
    if (!b.alive) continue;
    glm::ivec3 c = cell_of(grid, s.pos[b.node]);
    for (int q = 1; q <= 4; ++q)
      for (int dz = -q; dz <= q; ++dz)
        for (int dx = -q; dx <= q; ++dx) {
          glm::ivec3 t(c.x + dx, c.y - q, c.z + dz);
          if (valid(grid, t)) shadow[grid.index(t.x, t.y, t.z)] += float(std::ldexp(1.0, -q));
        }
  }
  for (Bud& b : s.buds) {
    if (!b.alive) continue;
    glm::ivec3 c = cell_of(grid, s.pos[b.node]);
    double sh = valid(grid, c) ? shadow[grid.index(c.x, c.y, c.z)] : 0.0;
    b.light = std::clamp(1.0 - 0.2 * sh, 0.0, 1.0);
  }

  // 2. Basipetal flow; parents precede children, so one reverse sweep accumulates.
  s.flow.assign(n, 0.0);
  for (const Bud& b : s.buds)
    if (b.alive) s.flow[b.node] += b.light, r.bud_light += b.light;
  std::vector<double> size(n, 0.0);
  for (size_t k = n; k-- > 1;) {
    if (!s.alive[k]) continue;
    size[k] += 1.0;
    s.flow[size_t(s.parent[k])] += s.flow[k];
    size[size_t(s.parent[k])] += size[k];
  }
  r.root_flow = s.flow[0];
  // Small starved lateral branches die (never the skeleton).
  std::vector<uint32_t> live_children(n, 0);
  for (size_t k = 1; k < n; ++k)
    if (s.alive[k]) ++live_children[size_t(s.parent[k])];
  for (size_t k = 1; k < n; ++k) {
    if (!s.alive[k] || s.fixed[k]) continue;
    size_t p = size_t(s.parent[k]);
    if (!s.alive[p] || live_children[p] < 2) continue;
    if (size[k] <= params.small_branch && s.flow[k] / size[k] < params.starve) {
      s.alive[k] = 0;  // descendants follow below (children have larger indices)
      ++r.branches_died;
    }
  }
  for (size_t k = 1; k < n; ++k)
    if (s.alive[k] && !s.alive[size_t(s.parent[k])]) s.alive[k] = 0;
  for (Bud& b : s.buds)
    if (b.alive && !s.alive[b.node]) b.alive = false, ++r.buds_died;

  // 3. Growth with pruning at the hull boundary.
  const double angle = glm::radians(params.branch_angle_deg), roll = glm::radians(params.phyllotaxis_deg);
  const double jitter = std::sin(glm::radians(params.jitter_deg));
  const size_t buds_now = s.buds.size();
  for (size_t k = 0; k < buds_now && s.pos.size() < params.max_nodes; ++k) {
    if (!s.buds[k].alive || s.buds[k].light < params.min_light) continue;
    Bud b = s.buds[k];
    glm::dvec3 noise(rng.symmetric(), rng.symmetric(), rng.symmetric());
    glm::dvec3 dir = b.heading + glm::dvec3(0, params.tropism, 0) + noise * jitter;
    dir = glm::length(dir) > 1e-9 ? glm::normalize(dir) : b.heading;
    glm::dvec3 p = s.pos[b.node], q = p + dir * b.length;
    if (segment_inside_hull(set, p, q)) {
      uint32_t node = uint32_t(s.pos.size());
      s.pos.push_back(q);
      s.parent.push_back(b.node);
      s.order.push_back(b.order);
      s.alive.push_back(1);
      s.fixed.push_back(0);
      s.flow.push_back(0.0);
      b.node = node;
      b.heading = dir;
      ++r.grown;
      if (b.light >= params.lateral_light && int(b.order) < params.max_order) {
        Bud lateral;
        lateral.node = node;
        lateral.heading = deflect(dir, angle, roll * double(b.laterals++) + rng.uniform(0.0, 0.3));
        lateral.length = b.length * params.lateral_scale;
        lateral.order = b.order + 1;
        if (lateral.length >= params.min_length) s.buds.push_back(lateral);
      }
    } else {
      ++r.pruned;
      b.length *= params.regrow_factor;
      r.regrowth.push_back({uint32_t(k), b.length});
      if (b.length < params.min_length) b.alive = false, ++r.buds_died;
    }
    s.buds[k] = b;
  }

  size_t occupied = 0, filled = 0;
  std::vector<uint8_t> has_node(grid.occupied.size(), 0);
  for (size_t k = 0; k < s.pos.size(); ++k) {
    if (!s.alive[k]) continue;
    glm::ivec3 c = cell_of(grid, s.pos[k]);
    if (valid(grid, c)) has_node[grid.index(c.x, c.y, c.z)] = 1;
  }
  for (size_t i = 0; i < grid.occupied.size(); ++i) occupied += grid.occupied[i], filled += grid.occupied[i] && has_node[i];
  r.fill = occupied ? double(filled) / double(occupied) : 0.0;
  ++s.year;
  return r;
}

std::vector<YearReport> grow(GrowthState& s, const ViewSet& set, const VoxelGrid& grid,
                             const GrowthParams& params, uint64_t seed,
                             const std::function<void(const GrowthState&)>& after_year) {
  std::vector<YearReport> reports;
  Rng rng(seed, /*stream=*/21);
  for (int y = 0; y < params.years; ++y) {
    reports.push_back(grow_year(s, set, grid, params, rng));
    if (after_year) after_year(s);
    bool any_bud = false;
    for (const Bud& b : s.buds) any_bud = any_bud || b.alive;
    if (!any_bud || reports.back().fill >= params.fill_target || s.pos.size() >= params.max_nodes) break;
  }
  return reports;
}

TreeGraph growth_graph(const GrowthState& s) {
  std::vector<int64_t> parent(s.pos.size(), -1);
  for (size_t k = 1; k < s.pos.size(); ++k)
    if (s.alive[k]) parent[k] = s.parent[k];
  TreeGraph g = rooted_tree(s.pos, parent, 0);
  assign_branch_orders(g);
  return g;
}

}  // namespace forest
