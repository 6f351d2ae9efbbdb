#include "generators/mesh/structural_lod.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "generators/mesh/branch_mesher.h"
#include "generators/mesh/mesh_lod.h"

#include <meshoptimizer.h>
#include <tbb/parallel_for.h>

namespace forest {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The error of removing a chain of base radius r: its width, the silhouette that vanishes.
constexpr float kRemovalError = 2.0f;

// Distance from p to triangle (a, b, c) (Ericson, Real-Time Collision Detection, 5.1.5).
float point_triangle_distance(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
  const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0f && d2 <= 0.0f) return glm::length(ap);
  const glm::vec3 bp = p - b;
  const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0f && d4 <= d3) return glm::length(bp);
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return glm::length(p - (a + ab * (d1 / (d1 - d3))));
  const glm::vec3 cp = p - c;
  const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0f && d5 <= d6) return glm::length(cp);
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return glm::length(p - (a + ac * (d2 / (d2 - d6))));
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f)
    return glm::length(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
  const float denom = 1.0f / (va + vb + vc);
  return glm::length(p - (a + ab * (vb * denom) + ac * (vc * denom)));
}

// How far the farthest vertex of `from` lies from the surface of `to` (one-sided Hausdorff
// over the vertices): what a simplification took away entirely counts its whole extent.
float farthest_vertex_distance(const Mesh& from, const Mesh& to) {
  std::vector<float> nearest(from.vertices.size(), std::numeric_limits<float>::infinity());
  tbb::parallel_for(size_t(0), from.vertices.size(), [&](size_t v) {
    const glm::vec3 p = from.vertices[v].position;
    for (size_t t = 0; t + 2 < to.indices.size(); t += 3)
      nearest[v] = std::min(nearest[v], point_triangle_distance(p, to.vertices[to.indices[t]].position,
                                                                to.vertices[to.indices[t + 1]].position,
                                                                to.vertices[to.indices[t + 2]].position));
  });
  float worst = 0.0f;
  for (float d : nearest) worst = std::max(worst, d);
  return worst;
}

// The distance a ring of radius r swept with n sides stands inside the true circle at most.
float ring_error(float r, int n) { return r * float(1.0 - std::cos(kPi / double(std::max(n, 3)))); }

// A planned level: the chains kept, the ring sides cap, and its two errors: the widest
// chain removed (a feature that vanishes) and the deepest ring coarsened (a surface that
// moves, to which the collapses after it add).
struct LevelPlan {
  std::vector<char> keep;
  int max_sides = 0;
  float removal_error = 0.0f;
  float ring_error = 0.0f;
  bool operator==(const LevelPlan& o) const { return keep == o.keep && max_sides == o.max_sides; }
};

// The sides a chain of base radius r gets when the trunk's (r_max) get n (ring_sides).
int sides_with_cap(float r, float r_max, const MesherParams& mesher, int n) {
  MesherParams p = mesher;
  p.max_sides = n;
  return ring_sides(r, r_max, p);
}

// What can go within `allowed` metres: every chain narrower than it (2r; a chain goes with
// everything growing on it, the root chains stay), and ring sides down to the smallest cap
// whose rings all stay within it.
LevelPlan plan_within(const std::vector<LodChain>& chains, const MesherParams& mesher, float r_max, float allowed) {
  LevelPlan plan;
  plan.keep.assign(chains.size(), 0);
  for (size_t c = 0; c < chains.size(); ++c) {
    const LodChain& ch = chains[c];
    const bool parent = ch.parent < 0 || plan.keep[size_t(ch.parent)];
    plan.keep[c] = parent && (ch.parent < 0 || kRemovalError * ch.base_radius > allowed);
    if (!plan.keep[c]) plan.removal_error = std::max(plan.removal_error, kRemovalError * ch.base_radius);
  }
  const int top = std::max(3, mesher.max_sides);
  plan.max_sides = top;
  for (int n = top - 1; n >= 3; --n) {
    float worst = 0.0f;
    for (size_t c = 0; c < chains.size(); ++c) {
      if (!plan.keep[c]) continue;
      const int s = sides_with_cap(chains[c].base_radius, r_max, mesher, n);
      if (chains[c].sides > 0 && uint32_t(s) < chains[c].sides) worst = std::max(worst, ring_error(chains[c].base_radius, s));
    }
    if (worst > allowed) break;
    plan.max_sides = n;
    plan.ring_error = std::max(plan.ring_error, worst);
  }
  return plan;
}

}  // namespace

std::vector<LodChain> lod_chains(const TreeGraph& graph, const BranchMeshInfo& info) {
  using namespace mesher_detail;
  const std::vector<Chain> chains = decompose_chains(graph, children_of(graph));
  std::vector<int32_t> chain_of(graph.nodes.size(), -1);
  std::vector<LodChain> out(chains.size());
  for (size_t c = 0; c < chains.size(); ++c) {
    const Chain& ch = chains[c];
    for (size_t i = ch.from_parent ? 1 : 0; i < ch.nodes.size(); ++i) chain_of[ch.nodes[i]] = int32_t(c);
    uint32_t base = ch.nodes[ch.from_parent && ch.nodes.size() > 1 ? 1 : 0];
    out[c].base_radius = graph.nodes[base].radius;
    out[c].parent = ch.from_parent ? chain_of[ch.nodes[0]] : -1;
  }
  for (const TubeRing& r : info.rings) {
    if (r.chain >= out.size()) continue;
    out[r.chain].rings += 1;
    out[r.chain].sides = std::max(out[r.chain].sides, r.sides);
  }
  return out;
}

TreeGraph prune_chains(const TreeGraph& graph, const std::vector<char>& keep) {
  using namespace mesher_detail;
  const std::vector<Chain> chains = decompose_chains(graph, children_of(graph));
  std::vector<char> node_kept(graph.nodes.size(), 0);
  for (size_t c = 0; c < chains.size() && c < keep.size(); ++c) {
    if (!keep[c]) continue;
    const Chain& ch = chains[c];
    for (size_t i = ch.from_parent ? 1 : 0; i < ch.nodes.size(); ++i) node_kept[ch.nodes[i]] = 1;
  }
  // A kept chain whose parent chain is gone would float: drop it too (parents come first).
  for (size_t n = 0; n < graph.nodes.size(); ++n) {
    int32_t p = graph.nodes[n].parent;
    if (p >= 0 && !node_kept[size_t(p)]) node_kept[n] = 0;
  }
  TreeGraph out;
  std::vector<int32_t> index(graph.nodes.size(), -1);
  for (size_t n = 0; n < graph.nodes.size(); ++n) {
    if (!node_kept[n]) continue;
    TreeNode node = graph.nodes[n];
    node.parent = node.parent < 0 ? -1 : index[size_t(node.parent)];
    index[n] = int32_t(out.nodes.size());
    out.nodes.push_back(node);
  }
  return out;
}

std::vector<MeshLod> structural_lods(const TreeGraph& graph, const MesherParams& mesher, const Mesh& lod0,
                                     const BranchMeshInfo& info0, const StructuralLodParams& params) {
  std::vector<MeshLod> lods;
  if (lod0.indices.empty()) return lods;
  const std::vector<LodChain> chains = lod_chains(graph, info0);
  float r_max = 0.0f;
  for (const LodChain& c : chains) r_max = std::max(r_max, c.base_radius);
  const size_t triangles0 = lod0.indices.size() / 3;
  const float scale0 = meshopt_simplifyScale(&lod0.vertices[0].position.x, lod0.vertices.size(), sizeof(Vertex));
  size_t previous = triangles0;
  float error = 0.0f;
  // How far edge collapses of LOD0 alone would move its surface to reach each target: that
  // much may go by structure (whole thin chains, coarser rings), and the collapses of what is
  // left then stay within the same distance.
  std::vector<size_t> targets;
  for (float fraction : params.fractions)
    targets.push_back(std::max<size_t>(1, size_t(double(triangles0) * double(fraction))));
  const std::vector<float> collapse = collapse_errors(lod0, targets, 0.25f * scale0);
  // The levels are independent given their targets: planned here, built in parallel (each
  // a pure function of its plan, so the result does not depend on the threads), then kept
  // in order where they save at least 10 % on the level before.
  std::vector<LevelPlan> plans(targets.size());
  for (size_t level = 0; level < targets.size(); ++level)
    plans[level] = plan_within(chains, mesher, r_max, collapse[level]);
  const LevelPlan full = plan_within(chains, mesher, r_max, 0.0f);  // all of LOD0
  std::vector<MeshLod> built(targets.size());
  tbb::parallel_for(size_t(0), targets.size(), [&](size_t level) {
    const LevelPlan& plan = plans[level];
    Mesh structural;
    if (!(plan == full)) {
      MesherParams coarse = mesher;
      coarse.max_sides = plan.max_sides;
      structural = mesh_branches(prune_chains(graph, plan.keep), coarse);
    }
    MeshLod lod = simplify_to(plan == full ? lod0 : structural, targets[level], collapse[level]);
    remove_back_to_back(lod.mesh);
    optimize_mesh(lod.mesh);
    // A vanished chain and a moved surface are different pixels: the larger counts; on the
    // surface the coarser rings and the collapses add up.
    lod.error = std::max(plan.removal_error, plan.ring_error + lod.error);
    built[level] = std::move(lod);
  });
  for (MeshLod& lod : built) {
    const size_t triangles = lod.mesh.indices.size() / 3;
    if (triangles == 0 || triangles * 10 > previous * 9) continue;
    error = std::max(error, lod.error);
    lod.error = error;
    previous = triangles;
    lods.push_back(std::move(lod));
  }
  // The sloppy level simplifies the last structural one; its error adds to that level's
  // (the distance to LOD0 is at most the sum).
  const size_t target = std::max<size_t>(1, size_t(double(triangles0) * double(params.sloppy_fraction)));
  if (target < previous) {
    const Mesh& source = lods.empty() ? lod0 : lods.back().mesh;
    MeshLod sloppy = sloppy_lod(source, target);
    const size_t triangles = sloppy.mesh.indices.size() / 3;
    if (triangles > 0 && triangles * 10 <= previous * 9) {
      // meshopt's sloppy error is its grid's: blind to the thin parts clustering removes whole
      // (at 160x96 a grove of fig2_1 at this level lost 11 % of its coverage while it claimed
      // 0.03 m). The farthest source vertex from the result is what went.
      sloppy.error = error + std::max(sloppy.error, farthest_vertex_distance(source, sloppy.mesh));
      lods.push_back(std::move(sloppy));
    }
  }
  return lods;
}

}  // namespace forest
