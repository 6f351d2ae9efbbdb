#include "generators/methods/particle_flow/particle_flow_sim.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "generators/core/rng.h"
#include "generators/methods/common/image_tree_util.h"

namespace forest {

namespace {

struct Particle {
  Phase phase;
  double count = 1.0;
  int64_t last_node = -1;
  bool active = true;
};

// Uniform hash grid over particle positions: neighbour queries in O(1) per particle.
struct SpatialHash {
  double cell;
  std::unordered_map<uint64_t, std::vector<uint32_t>> buckets;
  explicit SpatialHash(double c) : cell(c) {}
  static uint64_t key(glm::ivec3 c) {
    return (uint64_t(uint32_t(c.x)) * 73856093ull) ^ (uint64_t(uint32_t(c.y)) * 19349663ull << 1) ^
           (uint64_t(uint32_t(c.z)) * 83492791ull << 2);
  }
  glm::ivec3 cell_of(glm::dvec3 p) const { return glm::ivec3(glm::floor(p / cell)); }
  void insert(glm::dvec3 p, uint32_t i) { buckets[key(cell_of(p))].push_back(i); }
  template <class Fn>
  void near(glm::dvec3 p, Fn&& fn) const {
    glm::ivec3 c = cell_of(p);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          auto it = buckets.find(key(c + glm::ivec3(dx, dy, dz)));
          if (it != buckets.end())
            for (uint32_t j : it->second) fn(j);
        }
  }
};

glm::dvec3 unit_or_zero(glm::dvec3 v) {
  double l = glm::length(v);
  return l > 1e-12 ? v / l : glm::dvec3(0.0);
}

}  // namespace

std::vector<glm::dvec3> seed_particles(const DensityGrid& grid, size_t count, uint64_t seed) {
  std::vector<double> cdf(grid.alpha.size());
  double total = 0.0;
  for (size_t i = 0; i < grid.alpha.size(); ++i) cdf[i] = total += std::max(0.0, grid.alpha[i]);
  std::vector<glm::dvec3> out;
  if (!(total > 0.0)) return out;
  Rng rng(seed, /*stream=*/1);
  for (size_t k = 0; k < count; ++k) {
    double u = rng.uniform() * total;
    size_t i = size_t(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin());
    i = std::min(i, cdf.size() - 1);
    while (i > 0 && grid.alpha[i] <= 0.0) --i;  // never land in an empty voxel (rounding)
    glm::dvec3 r(rng.uniform(), rng.uniform(), rng.uniform());
    out.push_back(grid.corner(grid.cell_of_index(i)) + r * grid.cell);
  }
  return out;
}

FlowResult trace_particles(const DensityGrid& grid, const DirectionField3D& field, glm::dvec3 base,
                           const FlowParams& params, uint64_t seed) {
  FlowResult out;
  out.seeds = seed_particles(grid, params.particles, seed);
  double farthest = 0.0;
  for (glm::dvec3 s : out.seeds) farthest = std::max(farthest, glm::length(s - base));
  const int iterations = std::max(1, params.iterations);
  const double speed = params.speed > 0.0 ? params.speed : std::max(1e-3, 1.6 * farthest / iterations);
  const double merge = params.merge_radius > 0.0 ? params.merge_radius : 0.6 * grid.cell;
  const double attract = params.attract_radius > 0.0 ? params.attract_radius : 2.0 * grid.cell;
  const double arrival = params.arrival_radius > 0.0 ? params.arrival_radius : 2.0 * speed;
  const double segment = params.segment_length > 0.0 ? params.segment_length : 0.5 * grid.cell;

  std::vector<glm::dvec3> pos = {base};
  std::vector<int64_t> down = {-1};
  std::vector<int64_t> owner = {-1};  // particle that made each node
  int64_t making = -1;
  auto new_node = [&](glm::dvec3 p) {
    pos.push_back(p);
    down.push_back(-1);
    owner.push_back(making);
    return int64_t(pos.size() - 1);
  };
  SpatialHash traces(merge);  // trace nodes of earlier steps
  std::vector<Particle> ps(out.seeds.size());
  for (size_t i = 0; i < ps.size(); ++i) {
    ps[i].phase.x = out.seeds[i];
    making = int64_t(i);
    ps[i].last_node = new_node(out.seeds[i]);
  }
  for (size_t n = 1; n < pos.size(); ++n) traces.insert(pos[n], uint32_t(n));

  for (int it = 0; it < iterations; ++it) {
    size_t active = 0;
    for (const Particle& p : ps) active += p.active;
    out.active.push_back(active);
    if (active == 0) break;
    const int64_t first_node_this_step = int64_t(pos.size());

    // Nearest neighbour of every particle, frozen for the step.
    SpatialHash hash(attract);
    for (uint32_t i = 0; i < ps.size(); ++i)
      if (ps[i].active) hash.insert(ps[i].phase.x, i);
    std::vector<glm::dvec3> toward_neighbour(ps.size(), glm::dvec3(0.0));
    for (uint32_t i = 0; i < ps.size(); ++i) {
      if (!ps[i].active) continue;
      double best = attract;
      int64_t nb = -1;
      hash.near(ps[i].phase.x, [&](uint32_t j) {
        double d = glm::length(ps[j].phase.x - ps[i].phase.x);
        if (j != i && (d < best || (d == best && nb >= 0 && j < nb))) best = d, nb = j;
      });
      if (nb >= 0) toward_neighbour[i] = unit_or_zero(ps[size_t(nb)].phase.x - ps[i].phase.x);
    }

    for (uint32_t i = 0; i < ps.size(); ++i) {
      Particle& p = ps[i];
      if (!p.active) continue;
      const double m = params.mass * std::pow(p.count, 0.25);
      const glm::dvec3 nb = toward_neighbour[i];
      auto f = [&](double, const Phase& y) {
        glm::dvec3 b = unit_or_zero(base - y.x);
        glm::dvec3 u = params.w_base * b + params.w_neighbour * nb;
        if (!field.empty()) u += params.w_field * field.at(y.x);
        u = glm::length(u) > 1e-9 ? glm::normalize(u) : b;
        return Phase{y.v, (params.stiffness / m) * (speed * u - y.v)};
      };
      switch (params.integrator) {
        case Integrator::Euler: p.phase = euler_step(p.phase, double(it), 1.0, f); break;
        case Integrator::Heun: p.phase = heun_step(p.phase, double(it), 1.0, f); break;
        case Integrator::RK4: p.phase = rk4_step(p.phase, double(it), 1.0, f); break;
      }
      p.phase.x.y = std::max(p.phase.x.y, base.y);  // never below the ground
      if (glm::length(p.phase.x - base) < arrival) {
        down[size_t(p.last_node)] = 0;
        p.active = false;
        ++out.arrived;
      } else if (glm::length(p.phase.x - pos[size_t(p.last_node)]) >= segment) {
        making = int64_t(i);
        int64_t n = new_node(p.phase.x);
        down[size_t(p.last_node)] = n;
        p.last_node = n;
      }
    }

    // Merge particles closer than the threshold; they move on together.
    SpatialHash close(merge);
    for (uint32_t i = 0; i < ps.size(); ++i)
      if (ps[i].active) close.insert(ps[i].phase.x, i);
    for (uint32_t i = 0; i < ps.size(); ++i) {
      if (!ps[i].active) continue;
      std::vector<uint32_t> partners;
      close.near(ps[i].phase.x, [&](uint32_t j) {
        if (j > i && ps[j].active && glm::length(ps[j].phase.x - ps[i].phase.x) < merge) partners.push_back(j);
      });
      std::sort(partners.begin(), partners.end());
      for (uint32_t j : partners) {
        Particle &a = ps[i], &b = ps[j];
        if (!b.active) continue;
        double w = a.count + b.count;
        a.phase.x = (a.count * a.phase.x + b.count * b.phase.x) / w;
        a.phase.v = (a.count * a.phase.v + b.count * b.phase.v) / w;
        a.count = w;
        if (a.last_node >= first_node_this_step) {
          pos[size_t(a.last_node)] = a.phase.x;
        } else {
          making = int64_t(i);
          int64_t n = new_node(a.phase.x);
          down[size_t(a.last_node)] = n;
          a.last_node = n;
        }
        down[size_t(b.last_node)] = a.last_node;
        b.active = false;
        ++out.merges;
      }
    }

    // [ours] A particle that comes within the merge radius of another particle's trace joins
    // it: the same as merging with a particle that passed there earlier. Without this,
    // streams that follow the same attractor at the same speed never catch up and reach the
    // base side by side (a bush instead of a trunk). Targets whose path downstream leads to
    // the particle's own head are refused (no cycles).
    for (uint32_t i = 0; i < ps.size(); ++i) {
      Particle& p = ps[i];
      if (!p.active) continue;
      int64_t best = -1;
      double bd = merge;
      traces.near(p.phase.x, [&](uint32_t n) {
        double d = glm::length(pos[n] - p.phase.x);
        if (owner[n] != int64_t(i) && (d < bd || (d == bd && int64_t(n) < best))) bd = d, best = n;
      });
      if (best < 0) continue;
      int64_t head = best;
      for (size_t guard = 0; down[size_t(head)] >= 0 && guard < pos.size(); ++guard) head = down[size_t(head)];
      if (head == p.last_node) continue;
      down[size_t(p.last_node)] = best;
      p.active = false;
      ++out.trace_joins;
    }
    for (size_t n = size_t(first_node_this_step); n < pos.size(); ++n) traces.insert(pos[n], uint32_t(n));
  }
  size_t still = 0;
  for (Particle& p : ps)
    if (p.active) {
      down[size_t(p.last_node)] = 0;
      p.active = false;
      ++still;
    }
  out.forced_joins = still;
  if (out.active.empty() || out.active.back() != 0) out.active.push_back(still);
  out.graph = rooted_tree(pos, down, 0);
  assign_branch_orders(out.graph);
  return out;
}

}  // namespace forest
