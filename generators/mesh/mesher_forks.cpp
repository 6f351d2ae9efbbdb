// mesh_branches, part 2: where the branches at a fork are cut back to the bifurcation sphere
// (Neubert 2012 ch5) and the junction surface that joins the cut rings (junction.h).
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>

#include "generators/mesh/branch_mesher.h"
#include "generators/mesh/junction.h"
#include "generators/mesh/junction_uv.h"
#include "generators/tree/allometry.h"

namespace forest::mesher_detail {

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

void BranchMesher::drop_all(Fork& f) {
  for (const Entry& e : f.entries)
    if (e.kind == EntryKind::side) f.embedded.push_back(e.chain);
  f.entries.clear();
  std::sort(f.embedded.begin(), f.embedded.end());
}

size_t BranchMesher::neighbour(const ChainGeom& g, size_t i, int step) const {
  long j = long(i) + step;
  while (j > 0 && j + 1 < long(g.node.size()) && !is_fork_[g.node[size_t(j)]]) j += step;
  return size_t(std::clamp(j, 0L, long(g.node.size()) - 1));
}

Entry BranchMesher::make_entry(EntryKind kind, uint32_t c, size_t i, int step) const {
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

long BranchMesher::plan_cuts(const Fork& f, std::vector<Entry>& entries) const {
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

void BranchMesher::plan_forks() {
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

void BranchMesher::emit_junctions(Mesh& mesh, BranchMeshInfo& info, std::vector<uint32_t>& failed) {
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
    emit_junction_surface(f, tris, mesh, info);
    info.junction_triangles += tris.size();
    ++info.junctions;
  }
}

void BranchMesher::emit_junction_surface(const Fork& f, const std::vector<std::array<RingVertex, 3>>& tris,
                                         Mesh& mesh, const BranchMeshInfo& info) {
  // Junction corners are the ring vertices where they keep the tube's uv, else copies with
  // uv of their own (junction_uv.h); copies with the same uv are shared.
  std::vector<std::array<JunctionUvCorner, 3>> corners(tris.size());
  for (size_t t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Entry& e = f.entries[tris[t][k].ring];
      const TubeRing& r = info.rings[e.ring];
      JunctionUvCorner& c = corners[t][k];
      c.vertex = r.first_vertex + tris[t][k].index;
      c.position = mesh.vertices[c.vertex].position;
      c.on_tube = e.kind != EntryKind::side;
      c.tube_uv = mesh.vertices[c.vertex].uv;
      c.period = float(double(r.sides) * 2.0 * double(r.radius) * std::sin(kPi / double(r.sides)) /
                       double(p_.bark_tile_meters));
    }
  std::vector<std::array<glm::vec2, 3>> uvs = junction_uvs(corners, p_.bark_tile_meters);
  std::map<std::tuple<uint32_t, float, float>, uint32_t> copies;
  for (size_t t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t source = corners[t][k].vertex;
      const glm::vec2 uv = uvs[t][k];
      if (uv == mesh.vertices[source].uv) {  // the tube's own vertex, uv and all
        mesh.indices.push_back(source);
        continue;
      }
      auto [it, added] = copies.try_emplace({source, uv.x, uv.y}, uint32_t(mesh.vertices.size()));
      if (added) mesh.vertices.push_back(Vertex{mesh.vertices[source].position, mesh.vertices[source].normal, uv});
      mesh.indices.push_back(it->second);
    }
}

}  // namespace forest::mesher_detail
