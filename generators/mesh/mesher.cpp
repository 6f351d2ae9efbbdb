// mesh_branches, part 1: the graph's chains, their spline axes and the tube rings swept
// along them (fork planning and junctions: mesher_forks.cpp).
#include "generators/mesh/mesher.h"

#include <algorithm>
#include <cmath>

#include "generators/mesh/branch_mesher.h"
#include "generators/mesh/frames.h"

namespace forest {

namespace mesher_detail {

std::vector<Chain> decompose_chains(const TreeGraph& graph,
                                    const std::vector<std::vector<uint32_t>>& children) {
  std::vector<Chain> chains;
  std::vector<Chain> pending;  // side chains not yet followed, each holding [parent, child]
  for (uint32_t i = 0; i < graph.nodes.size(); ++i)
    if (graph.nodes[i].parent < 0 && !children[i].empty()) pending.push_back(Chain{{i}, false});
  std::reverse(pending.begin(), pending.end());
  while (!pending.empty()) {
    Chain chain = std::move(pending.back());
    pending.pop_back();
    std::vector<Chain> started;
    uint32_t cur = chain.nodes.back();
    while (!children[cur].empty()) {
      // Continue along the thickest child (lowest index on ties: deterministic).
      uint32_t next = children[cur][0];
      for (uint32_t c : children[cur])
        if (graph.nodes[c].radius > graph.nodes[next].radius) next = c;
      for (uint32_t c : children[cur])
        if (c != next) started.push_back(Chain{{cur, c}, true});
      chain.nodes.push_back(next);
      cur = next;
    }
    chains.push_back(std::move(chain));
    // Depth-first order keeps a branch's sub-branches near it in the vertex buffer.
    for (auto it = started.rbegin(); it != started.rend(); ++it) pending.push_back(std::move(*it));
  }
  return chains;
}

Mesh BranchMesher::run(BranchMeshInfo* info) {
  build_chains();
  if (p_.join_forks) plan_forks();
  else
    for (Fork& f : forks_) drop_all(f);
  // Emit; a fork whose junction cannot be built falls back to embedded starts, then again.
  for (;;) {
    Mesh mesh;
    BranchMeshInfo local;
    std::vector<uint32_t> failed;
    bool pieces_ok = emit_tubes(mesh, local, failed);
    if (pieces_ok) emit_junctions(mesh, local, failed);
    if (pieces_ok && failed.empty()) {
      local.chains = chains_.size();
      if (info) *info = std::move(local);
      return mesh;
    }
    if (failed.empty())  // cannot happen; join nothing rather than loop
      for (uint32_t f = 0; f < forks_.size(); ++f) failed.push_back(f);
    for (uint32_t f : failed) drop_all(forks_[f]);
  }
}

void BranchMesher::build_chains() {
  auto children = children_of(graph_);
  std::vector<Chain> chains = decompose_chains(graph_, children);
  float r_max = 0.0f;
  for (const Chain& c : chains) r_max = std::max(r_max, radius_of(c.from_parent ? c.nodes[1] : c.nodes[0]));
  through_.assign(graph_.nodes.size(), {kNone, 0});
  std::vector<uint32_t> fork_of(graph_.nodes.size(), kNone);
  for (const Chain& c : chains) {
    ChainGeom g;
    g.from_parent = c.from_parent;
    g.substeps = std::max(1, p_.spline_substeps);
    std::vector<glm::vec4> ctrl;
    for (size_t i = 0; i < c.nodes.size(); ++i) {
      uint32_t node = c.nodes[i];
      float r = (i == 0 && c.from_parent) ? radius_of(c.nodes[1]) : radius_of(node);
      glm::vec3 pos = graph_.nodes[node].position;
      if (i == 0 && c.from_parent) pos = anchor(node);
      bool duplicate = !ctrl.empty() && glm::length(pos - glm::vec3(ctrl.back())) < 1e-5f;
      if (!duplicate) {
        ctrl.emplace_back(pos, r);
        g.node.push_back(node);
      } else if (i + 1 == c.nodes.size()) {
        ctrl.back() = glm::vec4(pos, r);  // keep the true end
        g.node.back() = node;
      }
      if (i > 0 || !c.from_parent) through_[node] = {uint32_t(chains_.size()), uint32_t(ctrl.size() - 1)};
    }
    if (ctrl.size() < 2) {  // zero length: nothing to sweep
      chains_.push_back(std::move(g));
      continue;
    }
    g.sides = uint32_t(ring_sides(ctrl[0].w, r_max, p_));
    g.spline = BSpline(std::move(ctrl));
    // Arc length along the axis, tabulated densely.
    size_t n = size_t(g.last() * g.substeps) + 1;
    double v = 0.0;
    glm::vec4 prev = g.spline.point(0.0);
    for (size_t j = 0; j < n; ++j) {
      glm::vec4 q = g.spline.point(double(j) / g.substeps);
      if (j > 0) v += glm::length(glm::vec3(q) - glm::vec3(prev));
      g.dense_v.push_back(v);
      prev = q;
    }
    if (c.from_parent) {
      uint32_t f = fork_of[c.nodes[0]];
      if (f == kNone) {
        f = fork_of[c.nodes[0]] = uint32_t(forks_.size());
        forks_.push_back(Fork{c.nodes[0], anchor(c.nodes[0])});
      }
      forks_[f].embedded.push_back(uint32_t(chains_.size()));  // until planned
    }
    chains_.push_back(std::move(g));
  }
  // Arc length (so bark v) continues from the parent at the fork, so junctions are not
  // stretched across it.
  // Chains come parents first, so each parent's offset is final when its children read it.
  for (ChainGeom& g : chains_) {
    if (!g.from_parent || g.dense_v.empty()) continue;
    auto [t, i] = through_[g.node[0]];
    if (t == kNone || chains_[t].dense_v.empty()) continue;
    double offset = chains_[t].v_at(double(i));
    for (double& v : g.dense_v) v += offset;
  }
  for (Fork& f : forks_) f.through = through_[f.node].first;
  is_fork_.assign(graph_.nodes.size(), 0);
  for (const Fork& f : forks_) is_fork_[f.node] = 1;
}

glm::vec2 BranchMesher::ring_uv(uint32_t k, uint32_t sides, float radius, double arc) const {
  const double perimeter = double(sides) * 2.0 * double(radius) * std::sin(kPi / double(sides));
  const double tile = double(p_.bark_tile_meters);
  return glm::vec2(float((double(k) / double(sides) - 0.5) * perimeter / tile), float(-arc / tile));
}

glm::vec3 BranchMesher::anchor(uint32_t node) const {
  auto [t, i] = through_[node];
  if (t == kNone || t >= chains_.size() || chains_[t].node.size() < 2) return graph_.nodes[node].position;
  return glm::vec3(chains_[t].spline.point(double(i)));
}

void BranchMesher::emit_piece(const Piece& pc, Mesh& mesh, BranchMeshInfo& info) {
  const ChainGeom& g = chains_[pc.chain];
  std::vector<SplineSample> samples =
      sample_adaptive(g.spline, pc.s0, pc.s1, double(p_.max_bend_deg) * kPi / 180.0,
                      double(p_.radius_tolerance), g.substeps);
  Entry* start = pc.start == EndKind::junction ? &forks_[pc.start_fork].entries[pc.start_entry] : nullptr;
  Entry* end = pc.end == EndKind::junction ? &forks_[pc.end_fork].entries[pc.end_entry] : nullptr;
  if (start) samples.front() = SplineSample{pc.s0, start->center, start->ring_radius, start->axis};
  if (end) samples.back() = SplineSample{pc.s1, end->center, end->ring_radius, -end->axis};
  std::vector<glm::vec3> tangents;
  for (const SplineSample& s : samples) tangents.push_back(s.tangent);
  // A continuation starts with the incoming ring's frame carried across the fork, so that
  // the two tubes' u (and the junction's, which continues both) agree around the branch.
  glm::vec3 normal0 = any_perpendicular(tangents[0]);
  if (start && start->kind == EntryKind::continuation)
    for (const Entry& e : forks_[pc.start_fork].entries)
      if (e.kind == EntryKind::incoming && e.ring != kNone)
        normal0 = transport(info.rings[e.ring].normal, info.rings[e.ring].tangent, tangents[0]);
  std::vector<Frame> frames = parallel_transport(tangents, normal0);

  const uint32_t sides = g.sides;
  const uint32_t piece = uint32_t(info.pieces++);
  // A piece that ends at a tip ends in a point: its last ring becomes the apex of a cone
  // (the twig tapers off), which closes the tip without a cap.
  const size_t rings = pc.end == EndKind::tip ? samples.size() - 1 : samples.size();
  std::vector<uint32_t> first(samples.size());
  for (size_t i = 0; i < rings; ++i) {
    const SplineSample& s = samples[i];
    const Frame& fr = frames[i];
    float r = std::max(s.radius, p_.min_radius);
    first[i] = uint32_t(mesh.vertices.size());
    for (uint32_t k = 0; k <= sides; ++k) {
      double theta = 2.0 * kPi * double(k % sides) / double(sides);
      glm::vec3 dir = float(std::cos(theta)) * fr.normal + float(std::sin(theta)) * fr.binormal;
      mesh.vertices.push_back(Vertex{s.position + r * dir, glm::normalize(dir), ring_uv(k, sides, r, g.v_at(s.s))});
    }
    info.rings.push_back(TubeRing{g.node_near(s.s), pc.chain, piece, s.s, s.position, fr.tangent,
                                  fr.normal, r, sides, first[i]});
    if (i == 0 && start) start->ring = uint32_t(info.rings.size() - 1);
    if (i + 1 == samples.size() && end) end->ring = uint32_t(info.rings.size() - 1);
  }
  if (pc.start == EndKind::base) info.base_ring_sides += sides;
  // Quads between consecutive rings, counter-clockwise seen from outside:
  // (a_k, a_k+1, b_k) has normal ~ binormal x tangent = normal (outward).
  for (size_t i = 0; i + 1 < rings; ++i) {
    uint32_t a = first[i], b = first[i + 1];
    for (uint32_t k = 0; k < sides; ++k) {
      mesh.indices.insert(mesh.indices.end(), {a + k, a + k + 1, b + k});
      mesh.indices.insert(mesh.indices.end(), {a + k + 1, b + k + 1, b + k});
    }
  }
  if (pc.start == EndKind::embedded) {
    ++info.embedded_starts;
    // A flat cap closes a side branch that starts inside its parent. Its start ring is
    // centered on the parent's axis with the branch's radius, at most the parent's (pipe
    // model), so the cap and the first part of the branch lie inside the parent: the union
    // is closed (no hole) although the two surfaces interpenetrate. Used only where a fork
    // cannot be joined (branches almost parallel to another one, or too short to leave
    // the bifurcation sphere) or when joining is switched off.
    // The cap has its own copies of the ring's vertices: its uv are the disc's, to scale.
    const SplineSample& s = samples.front();
    const glm::vec2 centre = ring_uv(sides / 2, sides, 0.0f, g.v_at(s.s));
    const float r = std::max(s.radius, p_.min_radius);
    uint32_t c = uint32_t(mesh.vertices.size());
    info.start_cap_vertices.push_back(c);
    mesh.vertices.push_back(Vertex{s.position, -frames.front().tangent, centre});
    for (uint32_t k = 0; k < sides; ++k) {
      double theta = 2.0 * kPi * double(k) / double(sides);
      glm::vec2 disc(float(std::cos(theta)), float(std::sin(theta)));
      mesh.vertices.push_back(Vertex{mesh.vertices[first[0] + k].position, -frames.front().tangent,
                                     centre + disc * (r / p_.bark_tile_meters)});
    }
    for (uint32_t k = 0; k < sides; ++k)
      mesh.indices.insert(mesh.indices.end(), {c, c + 1 + (k + 1) % sides, c + 1 + k});
  }
  if (pc.end == EndKind::tip) {
    const SplineSample& s = samples.back();
    uint32_t apex = uint32_t(mesh.vertices.size());
    mesh.vertices.push_back(Vertex{s.position, frames.back().tangent, ring_uv(sides / 2, sides, 0.0f, g.v_at(s.s))});
    info.cap_vertices.push_back(apex);
    uint32_t last = first[rings - 1];
    for (uint32_t k = 0; k < sides; ++k)
      mesh.indices.insert(mesh.indices.end(), {last + k, last + k + 1, apex});
  }
}

bool BranchMesher::emit_tubes(Mesh& mesh, BranchMeshInfo& info, std::vector<uint32_t>& failed) {
  struct Cut {
    double s0, s1;  // the part of the chain inside a junction
    uint32_t fork;
    uint32_t entry0, entry1;  // entries ending / starting a piece (kNone: chain end)
  };
  std::vector<std::vector<Cut>> cuts(chains_.size());
  for (uint32_t fi = 0; fi < forks_.size(); ++fi) {
    const Fork& f = forks_[fi];
    if (f.entries.empty()) continue;
    Cut through{0.0, 0.0, fi, kNone, kNone};
    for (uint32_t k = 0; k < f.entries.size(); ++k) {
      const Entry& e = f.entries[k];
      if (e.kind == EntryKind::incoming) through.s0 = e.s_cut, through.entry0 = k;
      if (e.kind == EntryKind::continuation) through.s1 = e.s_cut, through.entry1 = k;
      if (e.kind == EntryKind::side) cuts[e.chain].push_back(Cut{0.0, e.s_cut, fi, kNone, k});
    }
    cuts[f.through].push_back(through);
  }
  std::vector<Piece> pieces;
  for (uint32_t c = 0; c < chains_.size(); ++c) {
    const ChainGeom& g = chains_[c];
    if (g.node.size() < 2) continue;
    auto& list = cuts[c];
    std::sort(list.begin(), list.end(), [](const Cut& a, const Cut& b) { return a.s0 < b.s0; });
    Piece pc;
    pc.chain = c;
    pc.s0 = 0.0;
    pc.start = g.from_parent ? EndKind::embedded : EndKind::base;
    for (const Cut& cut : list) {
      if (cut.entry0 == kNone && cut.s0 == 0.0 && pc.s0 == 0.0 && pc.start != EndKind::junction) {
        // The chain starts inside this junction (a side branch, or a fork at the root).
        pc.s0 = cut.s1;
        pc.start = EndKind::junction;
        pc.start_fork = cut.fork;
        pc.start_entry = cut.entry1;
        continue;
      }
      pc.s1 = cut.s0;
      pc.end = EndKind::junction;
      pc.end_fork = cut.fork;
      pc.end_entry = cut.entry0;
      if (!(pc.s1 > pc.s0 + 1e-6) || cut.entry0 == kNone) {
        failed.push_back(cut.fork);
        if (pc.start == EndKind::junction) failed.push_back(pc.start_fork);
        return false;
      }
      pieces.push_back(pc);
      pc = Piece{};
      pc.chain = c;
      pc.s0 = cut.s1;
      pc.start = EndKind::junction;
      pc.start_fork = cut.fork;
      pc.start_entry = cut.entry1;
    }
    pc.s1 = g.last();
    pc.end = EndKind::tip;
    if (!(pc.s1 > pc.s0 + 1e-6)) {
      if (pc.start == EndKind::junction) failed.push_back(pc.start_fork);
      return false;
    }
    pieces.push_back(pc);
  }
  for (const Piece& pc : pieces) emit_piece(pc, mesh, info);
  return true;
}

}  // namespace mesher_detail

int ring_sides(float r, float r_max, const MesherParams& params) {
  int lo = std::max(3, params.min_sides);
  int hi = std::max(lo, params.max_sides);
  if (!(r_max > 0.0f) || !(r > 0.0f)) return lo;
  float s = float(hi) * std::sqrt(std::min(1.0f, r / r_max));
  return std::clamp(int(std::lround(s)), lo, hi);
}

Mesh mesh_branches(const TreeGraph& graph, const MesherParams& params, BranchMeshInfo* info) {
  return mesher_detail::BranchMesher(graph, params).run(info);
}

}  // namespace forest
