#include "generators/mesh/mesher.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "generators/tree/allometry.h"
#include "generators/mesh/bspline.h"
#include "generators/mesh/frames.h"
#include "generators/mesh/junction.h"

namespace forest {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr uint32_t kNone = ~0u;

// A chain: graph nodes swept by one tube. `from_parent`: the first node is the parent the
// chain branches off, so its first ring uses the branch's own radius, not the parent's.
struct Chain {
  std::vector<uint32_t> nodes;
  bool from_parent = false;
};

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

// A chain's axis: its spline, the bark's v along it, and the graph node of every control
// point.
struct ChainGeom {
  std::vector<uint32_t> node;  // graph node of each control point (consecutive duplicates merged)
  BSpline spline;
  bool from_parent = false;
  uint32_t sides = 3;
  int substeps = 8;
  std::vector<double> dense_v;  // bark v at s = j / substeps
  double last() const { return spline.max_parameter(); }
  glm::vec3 control_pos(size_t i) const { return glm::vec3(spline.control(long(i))); }
  float control_radius(size_t i) const { return spline.control(long(i)).w; }
  double v_at(double s) const {
    double x = std::clamp(s * substeps, 0.0, double(dense_v.size() - 1));
    size_t j = std::min(size_t(x), dense_v.size() - 1);
    if (j + 1 >= dense_v.size()) return dense_v.back();
    return dense_v[j] + (dense_v[j + 1] - dense_v[j]) * (x - double(j));
  }
  uint32_t node_near(double s) const {
    return node[std::min(node.size() - 1, size_t(std::max(0.0, std::round(s))))];
  }
};

// One branch at a fork: the incoming one, the continuation, or a side chain.
enum class EntryKind { incoming, continuation, side };
struct Entry {
  EntryKind kind = EntryKind::side;
  uint32_t chain = 0;
  double s_fork = 0.0;   // parameter of the fork on this chain
  double s_bound = 0.0;  // the cut must stay between s_fork and this
  float max_dist = 0.0f;
  glm::vec3 leg{0.0f};   // unit direction of the first control-polygon leg away from the fork
  float radius = 0.0f;   // radius for the bifurcation sphere
  // The cut, once planned:
  double s_cut = 0.0;
  glm::vec3 center{0.0f};
  glm::vec3 axis{0.0f};  // unit, from the fork toward the ring center
  float ring_radius = 0.0f;
  uint32_t ring = kNone;  // index into the emitted rings
};

struct Fork {
  uint32_t node = 0;
  glm::vec3 center{0.0f};
  uint32_t through = kNone;  // chain passing through
  std::vector<Entry> entries;  // joined branches (empty: not joined)
  // Side chains that start closed inside the parent instead (before planning: all of them).
  std::vector<uint32_t> embedded;
};

enum class EndKind { base, embedded, junction, tip };
struct Piece {
  uint32_t chain = 0;
  double s0 = 0.0, s1 = 0.0;
  EndKind start = EndKind::base, end = EndKind::tip;
  uint32_t start_fork = kNone, start_entry = 0, end_fork = kNone, end_entry = 0;
};

// Finds s between from and bound (either direction) where |C(s) - center| first reaches dist.
bool find_cut(const ChainGeom& g, glm::vec3 center, double from, double bound, float dist, double* out) {
  const double step = 1.0 / double(g.substeps);
  const double dir = bound >= from ? 1.0 : -1.0;
  auto dist_at = [&](double s) { return glm::length(glm::vec3(g.spline.point(s)) - center); };
  if (dist_at(from) >= 0.5f * dist) return false;  // the axis misses the fork: no clean cut
  double prev = from;
  for (int j = 1;; ++j) {
    double s = from + dir * step * double(j);
    bool last = dir > 0 ? s >= bound : s <= bound;
    if (last) s = bound;
    if (dist_at(s) >= dist) {
      double lo = prev, hi = s;
      for (int it = 0; it < 30; ++it) {
        double mid = 0.5 * (lo + hi);
        (dist_at(mid) >= dist ? hi : lo) = mid;
      }
      *out = hi;
      return true;
    }
    if (last) return false;
    prev = s;
  }
}

class BranchMesher {
 public:
  BranchMesher(const TreeGraph& graph, const MesherParams& params) : graph_(graph), p_(params) {}

  Mesh run(BranchMeshInfo* info) {
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

 private:
  float radius_of(uint32_t node) const { return std::max(graph_.nodes[node].radius, p_.min_radius); }

  void build_chains() {
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
      // Bark v = ∫ ds / (2π r), tabulated densely along the axis.
      size_t n = size_t(g.last() * g.substeps) + 1;
      double v = 0.0;
      glm::vec4 prev = g.spline.point(0.0);
      for (size_t j = 0; j < n; ++j) {
        glm::vec4 q = g.spline.point(double(j) / g.substeps);
        if (j > 0) v += glm::length(glm::vec3(q) - glm::vec3(prev)) / (kPi * double(q.w + prev.w));
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
    // Bark v continues from the parent at the fork, so junctions are not stretched across it.
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

  // Where a side branch leaves its parent: the parent's axis at the fork node. The axis
  // smooths the skeleton and so passes near, not through, the node; starting the branch (and
  // centering the junction) on the axis keeps the branch attached to its parent's tube.
  glm::vec3 anchor(uint32_t node) const {
    auto [t, i] = through_[node];
    if (t == kNone || t >= chains_.size() || chains_[t].node.size() < 2) return graph_.nodes[node].position;
    return glm::vec3(chains_[t].spline.point(double(i)));
  }

  void drop_all(Fork& f) {
    for (const Entry& e : f.entries)
      if (e.kind == EntryKind::side) f.embedded.push_back(e.chain);
    f.entries.clear();
    std::sort(f.embedded.begin(), f.embedded.end());
  }

  // The next control point index from i (step ±1) that is a fork or an end of the chain.
  size_t neighbour(const ChainGeom& g, size_t i, int step) const {
    long j = long(i) + step;
    while (j > 0 && j + 1 < long(g.node.size()) && !is_fork_[g.node[size_t(j)]]) j += step;
    return size_t(std::clamp(j, 0L, long(g.node.size()) - 1));
  }

  // A branch at fork f along chain c, from control point i toward j.
  Entry make_entry(EntryKind kind, uint32_t c, size_t i, int step) const {
    const ChainGeom& g = chains_[c];
    Entry e;
    e.kind = kind;
    e.chain = c;
    e.s_fork = double(i);
    size_t j = neighbour(g, i, step);
    e.s_bound = double(j);
    bool to_end = (j == 0 && !g.from_parent) || j + 1 == g.node.size();
    glm::vec3 a = g.control_pos(i), b = g.control_pos(j);
    e.max_dist = (to_end ? p_.end_share : p_.fork_share) * glm::length(b - a);
    glm::vec3 leg = g.control_pos(size_t(long(i) + step)) - a;
    e.leg = glm::length(leg) > 0.0f ? glm::normalize(leg) : glm::vec3(0.0f);
    e.radius = kind == EntryKind::continuation ? g.control_radius(i + 1) : g.control_radius(i);
    return e;
  }

  // Cuts every entry where its axis leaves a sphere around the fork: first the largest
  // pairwise bifurcation sphere of the branches' first legs (Neubert 2012 ch5), grown while two
  // cut cross-sections, seen from the fork, still overlap (the axes curve, so the angles
  // between the cuts differ from those between the legs). Returns -1 when all cuts fit,
  // -2 when two parts of the through chain cannot be separated, else the entry to drop
  // (a side branch that cannot be cut or separated; the thinner of an overlapping pair).
  long plan_cuts(const Fork& f, std::vector<Entry>& entries) const {
    const double lo = double(p_.min_fork_angle_deg) * kPi / 180.0;
    const double hi = double(p_.max_fork_angle_deg) * kPi / 180.0;
    const double margin = double(p_.junction_margin_deg) * kPi / 180.0;
    double d = 0.0;
    for (size_t a = 0; a < entries.size(); ++a)
      for (size_t b = a + 1; b < entries.size(); ++b) {
        double gamma = std::acos(std::clamp(double(glm::dot(entries[a].leg, entries[b].leg)), -1.0, 1.0));
        d = std::max(d, bifurcation_sphere(entries[a].radius, entries[b].radius, gamma, lo, hi).radius);
      }
    for (int attempt = 0;; ++attempt) {
      for (size_t a = 0; a < entries.size(); ++a) {
        Entry& e = entries[a];
        const ChainGeom& g = chains_[e.chain];
        if (!find_cut(g, f.center, e.s_fork, e.s_bound, std::min(float(d), e.max_dist), &e.s_cut)) return long(a);
        glm::vec4 q = g.spline.point(e.s_cut);
        e.center = glm::vec3(q);
        e.axis = glm::normalize(e.center - f.center);
        e.ring_radius = std::max(q.w, p_.min_radius);
      }
      double worst = 0.0;
      size_t wa = 0, wb = 0;
      for (size_t a = 0; a < entries.size(); ++a)
        for (size_t b = a + 1; b < entries.size(); ++b) {
          const Entry &ea = entries[a], &eb = entries[b];
          double rho_a = std::atan(double(ea.ring_radius) / glm::length(ea.center - f.center));
          double rho_b = std::atan(double(eb.ring_radius) / glm::length(eb.center - f.center));
          double gamma = std::acos(std::clamp(double(glm::dot(ea.axis, eb.axis)), -1.0, 1.0));
          double overlap = rho_a + rho_b + margin - gamma;
          if (overlap > worst) worst = overlap, wa = a, wb = b;
        }
      if (worst <= 0.0) return -1;
      const Entry &ea = entries[wa], &eb = entries[wb];
      double gamma = std::acos(std::clamp(double(glm::dot(ea.axis, eb.axis)), -1.0, 1.0)) - margin;
      bool room = d < double(ea.max_dist) || d < double(eb.max_dist);
      if (attempt < 8 && room) {  // grow by at least 15%, at most 8 times (×2.7 or more)
        d = std::max(1.15 * d, bifurcation_sphere(ea.ring_radius, eb.ring_radius, gamma, lo, hi).radius);
        continue;
      }
      bool sa = ea.kind == EntryKind::side, sb = eb.kind == EntryKind::side;
      if (!sa && !sb) return -2;
      return long(sa && (!sb || ea.radius <= eb.radius) ? wa : wb);
    }
  }

  void plan_forks() {
    for (Fork& f : forks_) {
      if (f.through == kNone) continue;
      const ChainGeom& t = chains_[f.through];
      size_t i = through_[f.node].second;
      if (t.node.size() < 2 || i + 1 >= t.node.size()) continue;  // nothing continues
      std::vector<Entry> entries;
      if (i > 0) entries.push_back(make_entry(EntryKind::incoming, f.through, i, -1));
      entries.push_back(make_entry(EntryKind::continuation, f.through, i, +1));
      for (uint32_t c : f.embedded)
        if (chains_[c].node.size() >= 2) entries.push_back(make_entry(EntryKind::side, c, 0, +1));
      std::vector<uint32_t> embedded;
      for (uint32_t c : f.embedded)
        if (chains_[c].node.size() < 2) embedded.push_back(c);
      if (std::any_of(entries.begin(), entries.end(), [](const Entry& e) { return glm::length(e.leg) == 0.0f; })) {
        for (const Entry& e : entries)  // degenerate: leave it unjoined
          if (e.kind == EntryKind::side) embedded.push_back(e.chain);
        entries.clear();
      }
      // Plan, dropping side branches that cannot be separated, until all fit or none is left.
      bool ok = false;
      while (std::any_of(entries.begin(), entries.end(), [](const Entry& e) { return e.kind == EntryKind::side; })) {
        long drop = plan_cuts(f, entries);
        if (drop == -1) {
          ok = true;
          break;
        }
        if (drop == -2 || entries[size_t(drop)].kind != EntryKind::side) break;
        embedded.push_back(entries[size_t(drop)].chain);
        entries.erase(entries.begin() + drop);
      }
      if (!ok) {
        for (const Entry& e : entries)
          if (e.kind == EntryKind::side) embedded.push_back(e.chain);
        entries.clear();
      }
      std::sort(embedded.begin(), embedded.end());
      f.entries = std::move(entries);
      f.embedded = std::move(embedded);
    }
  }

  // Rings of one piece: adaptive samples with the junction rings' axes at joined ends.
  void emit_piece(const Piece& pc, Mesh& mesh, BranchMeshInfo& info) {
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
    std::vector<Frame> frames = parallel_transport(tangents, any_perpendicular(tangents[0]));

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
      float v = float(g.v_at(s.s));
      first[i] = uint32_t(mesh.vertices.size());
      for (uint32_t k = 0; k <= sides; ++k) {
        double theta = 2.0 * kPi * double(k % sides) / double(sides);
        glm::vec3 dir = float(std::cos(theta)) * fr.normal + float(std::sin(theta)) * fr.binormal;
        mesh.vertices.push_back(Vertex{s.position + r * dir, glm::normalize(dir),
                                       glm::vec2(float(k) / float(sides), v)});
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
      const SplineSample& s = samples.front();
      uint32_t c = uint32_t(mesh.vertices.size());
      info.start_cap_vertices.push_back(c);
      mesh.vertices.push_back(Vertex{s.position, -frames.front().tangent,
                                     glm::vec2(0.5f, float(g.v_at(s.s)))});
      for (uint32_t k = 0; k < sides; ++k)
        mesh.indices.insert(mesh.indices.end(), {c, first[0] + k + 1, first[0] + k});
    }
    if (pc.end == EndKind::tip) {
      const SplineSample& s = samples.back();
      uint32_t apex = uint32_t(mesh.vertices.size());
      mesh.vertices.push_back(Vertex{s.position, frames.back().tangent, glm::vec2(0.5f, float(g.v_at(s.s)))});
      info.cap_vertices.push_back(apex);
      uint32_t last = first[rings - 1];
      for (uint32_t k = 0; k < sides; ++k)
        mesh.indices.insert(mesh.indices.end(), {last + k, last + k + 1, apex});
    }
  }

  // Cuts every chain into pieces between joined forks and sweeps them. False (with the forks
  // to blame in `failed`) when two junctions would overlap along a chain.
  bool emit_tubes(Mesh& mesh, BranchMeshInfo& info, std::vector<uint32_t>& failed) {
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

  void emit_junctions(Mesh& mesh, BranchMeshInfo& info, std::vector<uint32_t>& failed) {
    std::vector<JunctionRing> rings;
    std::vector<std::array<RingVertex, 3>> tris;
    for (uint32_t fi = 0; fi < forks_.size(); ++fi) {
      const Fork& f = forks_[fi];
      if (f.entries.empty()) continue;
      rings.clear();
      for (const Entry& e : f.entries) {
        const TubeRing& r = info.rings[e.ring];
        JunctionRing jr;
        jr.axis = e.axis;
        for (uint32_t k = 0; k < r.sides; ++k) jr.points.push_back(mesh.vertices[r.first_vertex + k].position);
        rings.push_back(std::move(jr));
      }
      if (!join_rings(f.center, rings, &tris)) {
        failed.push_back(fi);
        continue;
      }
      for (const auto& t : tris) {
        for (int k = 0; k < 3; ++k) {
          const TubeRing& r = info.rings[f.entries[t[k].ring].ring];
          uint32_t index = r.first_vertex + t[k].index;
          // At the texture seam take the u = 1 copy when the triangle's other corners on this
          // ring lie on the far side of the seam.
          if (t[k].index == 0)
            for (int o = 0; o < 3; ++o)
              if (o != k && t[o].ring == t[k].ring && 2 * t[o].index > r.sides) index = r.first_vertex + r.sides;
          mesh.indices.push_back(index);
        }
      }
      info.junction_triangles += tris.size();
      ++info.junctions;
    }
  }

  const TreeGraph& graph_;
  const MesherParams& p_;
  std::vector<ChainGeom> chains_;
  std::vector<std::pair<uint32_t, uint32_t>> through_;  // node -> (chain, control point) passing through
  std::vector<char> is_fork_;
  std::vector<Fork> forks_;
};

}  // namespace

int ring_sides(float r, float r_max, const MesherParams& params) {
  int lo = std::max(3, params.min_sides);
  int hi = std::max(lo, params.max_sides);
  if (!(r_max > 0.0f) || !(r > 0.0f)) return lo;
  float s = float(hi) * std::sqrt(std::min(1.0f, r / r_max));
  return std::clamp(int(std::lround(s)), lo, hi);
}

Mesh mesh_branches(const TreeGraph& graph, const MesherParams& params, BranchMeshInfo* info) {
  return BranchMesher(graph, params).run(info);
}

Mesh make_leaf_card(LeafShape shape) {
  const float w = leaf_card_aspect(shape);
  // Counter-clockwise seen from +Z: base left, base right, tip right, tip left.
  const glm::vec2 corners[4] = {{-0.5f * w, 0.0f}, {0.5f * w, 0.0f}, {0.5f * w, 1.0f}, {-0.5f * w, 1.0f}};
  Mesh card;
  for (const glm::vec2& p : corners) {
    Vertex v;
    v.position = glm::vec3(p, 0.0f);
    v.normal = glm::vec3(0.0f, 0.0f, 1.0f);
    v.uv = glm::vec2(0.5f + p.x / w, 1.0f - p.y);  // texture: leaf upright, tip at the top
    card.vertices.push_back(v);
  }
  card.indices = {0, 1, 2, 0, 2, 3};
  return card;
}

glm::vec3 leaf_to_model(const LeafPlacement& leaf, glm::vec3 local) {
  return leaf.position + leaf.rotation * (local * leaf.scale);
}

glm::vec4 bounding_sphere(const Mesh& branches, const Mesh& leaf_card,
                          const std::vector<LeafPlacement>& leaves) {
  std::vector<glm::vec3> pts;
  pts.reserve(branches.vertices.size() + leaves.size() * leaf_card.vertices.size());
  for (const Vertex& v : branches.vertices) pts.push_back(v.position);
  for (const LeafPlacement& l : leaves)
    for (const Vertex& v : leaf_card.vertices) pts.push_back(leaf_to_model(l, v.position));
  if (pts.empty()) return glm::vec4(0.0f);

  auto farthest = [&](glm::dvec3 from) {
    size_t best = 0;
    double best_d = -1.0;
    for (size_t i = 0; i < pts.size(); ++i) {
      double d = glm::length(glm::dvec3(pts[i]) - from);
      if (d > best_d) best_d = d, best = i;
    }
    return glm::dvec3(pts[best]);
  };
  // Ritter (1990): a diameter guess from two far points, then grow toward outliers.
  glm::dvec3 a = farthest(glm::dvec3(pts[0]));
  glm::dvec3 b = farthest(a);
  glm::dvec3 c = (a + b) * 0.5;
  double r = glm::length(b - a) * 0.5;
  for (const glm::vec3& p : pts) {
    glm::dvec3 q(p);
    double d = glm::length(q - c);
    if (d > r) {
      double nr = (r + d) * 0.5;
      c += (q - c) * ((nr - r) / d);
      r = nr;
    }
  }
  // Exact radius about the float center, with a margin for float rounding by consumers.
  glm::vec3 cf(c);
  double rmax = 0.0;
  for (const glm::vec3& p : pts) rmax = std::max(rmax, glm::length(glm::dvec3(p) - glm::dvec3(cf)));
  return glm::vec4(cf, float(rmax * (1.0 + 1e-6) + 1e-6));
}

size_t count_boundary_edges(const Mesh& mesh) {
  // Weld by exact position, then count undirected edges.
  std::map<std::array<float, 3>, uint32_t> ids;
  std::vector<uint32_t> weld(mesh.vertices.size());
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    const glm::vec3& p = mesh.vertices[i].position;
    weld[i] = ids.emplace(std::array<float, 3>{p.x, p.y, p.z}, uint32_t(ids.size())).first->second;
  }
  std::map<std::pair<uint32_t, uint32_t>, int> uses;
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      uint32_t a = weld[mesh.indices[t + size_t(k)]], b = weld[mesh.indices[t + size_t((k + 1) % 3)]];
      uses[{std::min(a, b), std::max(a, b)}]++;
    }
  size_t boundary = 0;
  for (const auto& [edge, n] : uses) boundary += n == 1;
  return boundary;
}

}  // namespace forest
