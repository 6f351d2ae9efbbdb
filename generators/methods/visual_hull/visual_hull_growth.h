// Open L-system growth inside the visual hull (Shlyakhter 2001 step 4; the source lost its numbers,
// so every parameter is [ours]). The hull skeleton is the axiom: its nodes are fixed
// internodes, its tips carry apical buds and its other nodes lateral buds. One iteration is
// one year, with the three environmental rules of the paper:
//   1. light: every bud casts shadow into the cells of a pyramid below it (shadow
//      propagation, as in self-organizing tree models); a bud's light is 1 - 0.2 * shadow,
//      clamped to [0, 1];
//   2. basipetal flow: the light of the buds flows down to the base, each node collecting the
//      light of its subtree (conserved: the base receives the sum); a small lateral branch
//      whose light per internode is below `starve` dies;
//   3. growth with pruning: every lit bud grows one internode (A -> F [&(angle) /(137.5) A] A:
//      an apical step and a lateral bud). A new internode that leaves the hull (exact segment
//      test) is pruned; the bud at the cut keeps its place and regrows next year with length
//      regrow_factor * pruned length; a bud whose length falls below min_length dies.
// Iterate for `years`, or until the foliage fills the hull's voxels to `fill_target`.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "generators/core/rng.h"
#include "generators/methods/visual_hull/visual_hull_skeleton.h"

namespace forest {

struct GrowthParams {
  int years = 6;
  double internode = 0.3;        // meters, first length of a new bud
  double branch_angle_deg = 45.0;
  double phyllotaxis_deg = 137.5;
  double lateral_scale = 0.8;    // lateral bud length = parent bud length * this
  double regrow_factor = 0.8;    // pruned bud regrows this fraction of the pruned length
  double min_length = 0.05;      // meters; shorter buds die
  double tropism = 0.15;         // pull of the heading toward +Y per internode
  double jitter_deg = 12.0;
  double min_light = 0.05;       // buds with less light do not grow
  double lateral_light = 0.35;   // buds with less light grow no lateral
  double starve = 0.12;          // light per internode below which a small branch dies
  int small_branch = 6;          // "small" = at most this many internodes
  int max_order = 4;
  double fill_target = 0.9;      // fraction of hull cells holding a node that ends growth
  size_t max_nodes = 60000;
};

struct Bud {
  uint32_t node = 0;
  glm::dvec3 heading{0.0, 1.0, 0.0};
  double length = 0.3;
  uint32_t order = 1;
  uint32_t laterals = 0;  // laterals made so far (phyllotaxis roll)
  bool alive = true;
  double light = 0.0;
};

struct GrowthState {
  std::vector<glm::dvec3> pos;
  std::vector<int64_t> parent;   // -1 for node 0
  std::vector<uint32_t> order;
  std::vector<uint8_t> alive;    // nodes of dead branches are kept (indices stay) but dead
  std::vector<uint8_t> fixed;    // skeleton nodes: never die
  std::vector<Bud> buds;
  std::vector<double> flow;      // basipetal light of the last year, per node
  int year = 0;
};

struct YearReport {
  size_t grown = 0;
  size_t pruned = 0;
  size_t buds_died = 0;
  size_t branches_died = 0;
  double bud_light = 0.0;   // sum of the light of all live buds
  double root_flow = 0.0;   // light arriving at the base (= bud_light)
  double fill = 0.0;        // fraction of hull cells holding a live node
  std::vector<std::pair<uint32_t, double>> regrowth;  // (bud, new length) of pruned buds
};

GrowthState start_growth(const HullSkeleton& skeleton, const GrowthParams& params);
YearReport grow_year(GrowthState& state, const ViewSet& set, const VoxelGrid& grid,
                     const GrowthParams& params, Rng& rng);
// Runs the years; `after_year` (optional) sees the state after each one. Bounded by
// params.years and params.max_nodes.
std::vector<YearReport> grow(GrowthState& state, const ViewSet& set, const VoxelGrid& grid,
                             const GrowthParams& params, uint64_t seed,
                             const std::function<void(const GrowthState&)>& after_year = {});

// Live nodes as a TreeGraph (root first, parent < child).
TreeGraph growth_graph(const GrowthState& state);

}  // namespace forest
