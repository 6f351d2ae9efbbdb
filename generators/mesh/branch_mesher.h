// Internals of mesh_branches (mesher.h), shared by mesher.cpp (chains and their tube rings)
// and mesher_forks.cpp (fork planning and junction surfaces). Not for use outside
// generators/mesh.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "generators/mesh/bspline.h"
#include "generators/mesh/junction.h"
#include "generators/mesh/mesher.h"

namespace forest::mesher_detail {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr uint32_t kNone = ~0u;

// A chain: graph nodes swept by one tube. `from_parent`: the first node is the parent the
// chain branches off, so its first ring uses the branch's own radius, not the parent's.
struct Chain {
  std::vector<uint32_t> nodes;
  bool from_parent = false;
};

// Chains of the graph, parents first: each follows its thickest child, the other children
// start chains of their own.
std::vector<Chain> decompose_chains(const TreeGraph& graph,
                                    const std::vector<std::vector<uint32_t>>& children);

// A chain's axis: its spline, the arc length along it (bark v before the tile scale), and
// the graph node of every control point.
struct ChainGeom {
  std::vector<uint32_t> node;  // graph node of each control point (consecutive duplicates merged)
  BSpline spline;
  bool from_parent = false;
  uint32_t sides = 3;
  int substeps = 8;
  std::vector<double> dense_v;  // arc length (m) at s = j / substeps, from the tree's base
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
bool find_cut(const ChainGeom& g, glm::vec3 center, double from, double bound, float dist, double* out);

class BranchMesher {
 public:
  BranchMesher(const TreeGraph& graph, const MesherParams& params) : graph_(graph), p_(params) {}
  Mesh run(BranchMeshInfo* info);

 private:
  float radius_of(uint32_t node) const { return std::max(graph_.nodes[node].radius, p_.min_radius); }

  // Chains, their spline axes, bark v along them, and the forks where side chains start.
  void build_chains();

  // Where a side branch leaves its parent: the parent's axis at the fork node. The axis
  // smooths the skeleton and so passes near, not through, the node; starting the branch (and
  // centering the junction) on the axis keeps the branch attached to its parent's tube.
  glm::vec3 anchor(uint32_t node) const;

  // Bark uv of vertex k of a ring (mesher.h): u along the ring's polygon from its middle
  // vertex, v = −arc / tile. Radius 0 gives the ring's middle, (0, v).
  glm::vec2 ring_uv(uint32_t k, uint32_t sides, float radius, double arc) const;

  // Unjoins a fork: its side branches start closed inside the parent instead.
  void drop_all(Fork& f);

  // The next control point index from i (step ±1) that is a fork or an end of the chain.
  size_t neighbour(const ChainGeom& g, size_t i, int step) const;

  // A branch at fork f along chain c, from control point i toward j.
  Entry make_entry(EntryKind kind, uint32_t c, size_t i, int step) const;

  // Cuts every entry where its axis leaves a sphere around the fork: first the largest
  // pairwise bifurcation sphere of the branches' first legs (Neubert 2012 ch5), grown while two
  // cut cross-sections, seen from the fork, still overlap (the axes curve, so the angles
  // between the cuts differ from those between the legs). Returns -1 when all cuts fit,
  // -2 when two parts of the through chain cannot be separated, else the entry to drop
  // (a side branch that cannot be cut or separated; the thinner of an overlapping pair).
  long plan_cuts(const Fork& f, std::vector<Entry>& entries) const;

  // Plans the cuts of every fork, dropping side branches that cannot be separated; a fork
  // left with none is not joined.
  void plan_forks();

  // Rings of one piece: adaptive samples with the junction rings' axes at joined ends.
  void emit_piece(const Piece& pc, Mesh& mesh, BranchMeshInfo& info);

  // Cuts every chain into pieces between joined forks and sweeps them. False (with the forks
  // to blame in `failed`) when two junctions would overlap along a chain.
  bool emit_tubes(Mesh& mesh, BranchMeshInfo& info, std::vector<uint32_t>& failed);

  // Joins the cut rings of every planned fork; a fork whose rings cannot be joined goes to
  // `failed` (and is retried unjoined).
  void emit_junctions(Mesh& mesh, BranchMeshInfo& info, std::vector<uint32_t>& failed);

  // The joined fork's triangles, on the ring vertices where they keep their tube's uv and
  // on copies with uv of their own elsewhere (junction_uvs, junction_uv.h).
  void emit_junction_surface(const Fork& f, const std::vector<std::array<RingVertex, 3>>& tris, Mesh& mesh,
                             const BranchMeshInfo& info);

  const TreeGraph& graph_;
  const MesherParams& p_;
  std::vector<ChainGeom> chains_;
  std::vector<std::pair<uint32_t, uint32_t>> through_;  // node -> (chain, control point) passing through
  std::vector<char> is_fork_;
  std::vector<Fork> forks_;
};

}  // namespace forest::mesher_detail
