// Species keys of method "mig" (all optional unless marked; ranges are checked):
//   name, seed, nodes (K), spacing (d, m; 0 = from K), reach (longest Yao edge / d), root
//   ([x, y, z]), shell (d_e, m), subgraph_nodes (k), subgraph_radius (r, m), shrink (a),
//   trunk_height (m, [ours]: a straight trunk before level 1, 0 = none) and trunk_sources =
//   "top" | "all" (level-1 paths leave the trunk at its top, or at any of its nodes),
//   [[volume]] tables (see graph_volume.h; required), [[level]] tables (required, level 1
//   first): b, alpha (deg), rotate (deg, + = down), direction ([x, y, z]), around_all;
//   and the skeleton style keys of graph_skeleton.h.
#include "generators/methods/mig/mig_method.h"
#include "generators/core/limits.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "generators/core/rng.h"
#include "generators/methods/common/graph_dijkstra.h"
#include "generators/methods/common/graph_poisson.h"
#include "generators/methods/common/graph_skeleton.h"
#include "generators/methods/common/graph_yao.h"

namespace forest {

namespace {

constexpr float kPi = 3.14159265358979323846f;

struct Endpoint {
  uint32_t node = 0;       // index in the tree
  glm::vec3 position{0.0f};
  glm::vec3 graph_root{0.0f};  // R of the graph it was chosen in
};

// Rotation of v about unit axis by angle (Rodrigues).
glm::vec3 rotate_about(glm::vec3 v, glm::vec3 axis, float angle) {
  float c = std::cos(angle), s = std::sin(angle);
  return v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1.0f - c);
}

// Tilts v away from +Y by `angle` about the horizontal axis up × v (+ = down).
glm::vec3 rotate_down(glm::vec3 v, float angle) {
  glm::vec3 axis = glm::cross(glm::vec3(0, 1, 0), v);
  if (glm::length(axis) < 1e-6f) axis = glm::vec3(0, 0, -1);
  return glm::normalize(rotate_about(v, glm::normalize(axis), angle));
}

// Graph of `root` (node 0) and up to `count` Poisson nodes inside, spacing d.
// The graph's nodes: `stem` (a vertical run of points from the root; just the root when
// there is no trunk), then the Poisson-disc points at least d from the stem's segment.
YaoGraph make_graph(const std::vector<glm::vec3>& stem, const InsideFn& inside, Box box, size_t count, float d,
                    float reach, Rng& rng) {
  std::vector<glm::vec3> pts = poisson_disc(inside, box, count, d, rng, 40 * count + 1000);
  std::vector<glm::vec3> nodes = stem;
  nodes.reserve(pts.size() + stem.size());
  const glm::vec3 root = stem.front();
  const float top = stem.back().y - root.y;
  for (glm::vec3 p : pts) {
    glm::vec3 q = root + glm::vec3(0.0f, std::clamp(p.y - root.y, 0.0f, top), 0.0f);
    if (glm::length(p - q) >= d) nodes.push_back(p);
  }
  return build_yao8(std::move(nodes), reach * d);
}

// Picks up to b distinct candidates (partial Fisher–Yates).
std::vector<uint32_t> pick(std::vector<uint32_t> candidates, size_t b, Rng& rng) {
  size_t m = std::min(b, candidates.size());
  for (size_t i = 0; i < m; ++i) {
    size_t j = i + size_t(rng.uniform() * double(candidates.size() - i));
    std::swap(candidates[i], candidates[std::min(j, candidates.size() - 1)]);
  }
  candidates.resize(m);
  return candidates;
}

// Adds the least-cost path endpoint -> (first node already in the tree) to the tree, top down.
uint32_t add_path(const YaoGraph& g, const ShortestPaths& sp, uint32_t endpoint,
                  std::vector<int32_t>& to_tree, TreeGraph& tree, uint32_t order) {
  std::vector<uint32_t> chain;
  uint32_t v = endpoint;
  while (to_tree[v] < 0) {  // ends at the graph's root, mapped before any path is added
    chain.push_back(v);
    v = uint32_t(sp.parent[v]);
  }
  for (size_t i = chain.size(); i-- > 0;) {
    TreeNode node;
    node.position = g.positions[chain[i]];
    node.parent = to_tree[v];
    node.order = order;
    to_tree[chain[i]] = int32_t(tree.nodes.size());
    tree.nodes.push_back(node);
    v = chain[i];
  }
  return uint32_t(to_tree[endpoint]);
}

}  // namespace

TreeGraph grow_mig(const MigParams& P, uint64_t seed, MigStats* stats) {
  MigStats st;
  TreeGraph tree;
  TreeNode root;
  root.position = P.root;
  tree.nodes.push_back(root);

  // ---- level 1: the user's volume ----
  std::vector<Shape> crown;
  for (const Shape& s : P.volume)
    if (s.endpoints) crown.push_back(s);
  Rng rng(seed, 1);
  Box box = volume_bounds(P.volume);
  InsideFn inside = [&](glm::vec3 p) { return volume_contains(P.volume, p); };
  float d = P.spacing > 0.0f ? P.spacing : spacing_for_count(estimate_volume(inside, box, rng), P.nodes);
  if (!(d > 0.0f)) throw InputError("mig: the level-1 volume is empty");
  // The straight trunk (graph nodes 0..m, tree nodes 0..m): R, then every d up to its top.
  std::vector<glm::vec3> trunk{P.root};
  if (P.trunk_height > 0.0f) {
    int steps = std::max(1, int(std::ceil(P.trunk_height / d)));
    for (int i = 1; i <= steps; ++i)
      trunk.push_back(P.root + glm::vec3(0.0f, P.trunk_height * float(i) / float(steps), 0.0f));
  }
  YaoGraph g = make_graph(trunk, inside, box, P.nodes, d, P.reach, rng);
  st.graph_nodes += g.size();
  const uint32_t trunk_nodes = uint32_t(trunk.size());
  std::vector<int32_t> to_tree(g.size(), -1);
  to_tree[0] = 0;
  for (uint32_t i = 1; i < trunk_nodes; ++i) {
    TreeNode node;
    node.position = trunk[i];
    node.parent = int32_t(i - 1);
    tree.nodes.push_back(node);
    to_tree[i] = int32_t(i);
  }
  std::vector<uint32_t> sources;
  if (P.trunk_sources_all && trunk_nodes > 1)
    for (uint32_t i = 1; i < trunk_nodes; ++i) sources.push_back(i);
  else
    sources.push_back(trunk_nodes - 1);
  // Trunk nodes that are not sources are no way through: paths leave the trunk at a source.
  std::vector<char> blocked(g.size(), 0);
  for (uint32_t i = 0; i < trunk_nodes; ++i) blocked[i] = 1;
  for (uint32_t s : sources) blocked[s] = 0;
  ShortestPaths sp = dijkstra(
      g, sources,
      [&](uint32_t, uint32_t e) {
        return blocked[g.targets[e]] ? std::numeric_limits<float>::infinity() : g.lengths[e];
      },
      [](uint32_t, int32_t, const ShortestPaths&) {});
  std::vector<uint32_t> candidates;
  for (uint32_t v = trunk_nodes; v < g.size(); ++v) {
    glm::vec3 p = g.positions[v];
    if (!volume_contains(crown, p)) continue;
    if (P.shell > 0.0f && !in_surface_shell(crown, p, P.shell)) continue;
    if (sp.reached(v))
      candidates.push_back(v);
    else
      ++st.unreachable;
  }
  std::vector<Endpoint> prev;
  for (uint32_t e : pick(candidates, size_t(P.levels.at(0).branching), rng))
    prev.push_back({add_path(g, sp, e, to_tree, tree, 0), g.positions[e], P.root});
  std::vector<Endpoint> all = prev;

  // ---- levels 2..L: cone-shaped subgraphs around earlier endpoints ----
  float r = P.subgraph_radius;
  for (size_t level = 1; level < P.levels.size(); ++level) {
    const MigLevel& L = P.levels[level];
    const std::vector<Endpoint> around = L.around_all ? all : prev;
    std::vector<Endpoint> next;
    const double cone_volume = 2.0 / 3.0 * kPi * double(r) * r * r * (1.0 - std::cos(double(L.alpha)));
    const float ds = spacing_for_count(cone_volume, P.subgraph_nodes);
    for (size_t i = 0; i < around.size(); ++i) {
      const Endpoint& e = around[i];
      glm::vec3 vg = e.position - e.graph_root;
      vg = L.direction ? glm::normalize(*L.direction)
                       : (glm::length(vg) > 1e-6f ? glm::normalize(vg) : glm::vec3(0, 1, 0));
      if (L.rotate != 0.0f) vg = rotate_down(vg, L.rotate);
      Shape cone;
      cone.kind = ShapeKind::SpherePortion;
      cone.center = e.position;
      cone.axis = vg;
      cone.radius = r;
      cone.angle = L.alpha;
      Rng sub_rng(hash64(seed, level, i), 2);
      YaoGraph sg = make_graph(
          std::vector<glm::vec3>{e.position}, [&](glm::vec3 p) { return shape_contains(cone, p); }, shape_bounds(cone),
          P.subgraph_nodes, ds, P.reach, sub_rng);
      st.graph_nodes += sg.size();
      ++st.subgraphs;
      const uint32_t source = 0;
      ShortestPaths ssp = dijkstra_lengths(sg, std::span<const uint32_t>(&source, 1));
      std::vector<uint32_t> reached;
      for (uint32_t v = 1; v < sg.size(); ++v) {
        if (ssp.reached(v))
          reached.push_back(v);
        else
          ++st.unreachable;
      }
      std::vector<int32_t> sub_to_tree(sg.size(), -1);
      sub_to_tree[0] = int32_t(e.node);
      for (uint32_t v : pick(reached, size_t(L.branching), sub_rng))
        next.push_back({add_path(sg, ssp, v, sub_to_tree, tree, uint32_t(level)), sg.positions[v],
                        e.position});
    }
    all.insert(all.end(), next.begin(), next.end());
    prev = std::move(next);
    r *= P.shrink;
  }
  st.endpoints = all.size();
  if (stats) *stats = st;
  return tree;
}

namespace {

MigParams read_params(const TomlTable& t) {
  MigParams P;
  P.nodes = size_t(t.integer("nodes", 3000, 10, 2000000));
  P.spacing = float(t.number("spacing", 0.0, 0.0, 100.0));
  P.reach = float(t.number("reach", 4.0, 1.5, 20.0));
  P.root = t.vec3("root", glm::vec3(0.0f), -1000.0, 1000.0);
  P.shell = float(t.number("shell", 0.0, 0.0, 1000.0));
  P.subgraph_nodes = size_t(t.integer("subgraph_nodes", 150, 4, 100000));
  P.subgraph_radius = float(t.number("subgraph_radius", 2.0, 1e-3, 1000.0));
  P.shrink = float(t.number("shrink", 0.7, 0.05, 2.0));
  P.trunk_height = float(t.number("trunk_height", 0.0, 0.0, 1000.0));
  std::string sources = t.choice("trunk_sources", "top", {"top", "all"});
  if (t.has("trunk_sources") && P.trunk_height <= 0.0f) t.fail("trunk_sources", "needs trunk_height > 0");
  P.trunk_sources_all = sources == "all";
  for (const TomlTable& v : t.tables("volume")) P.volume.push_back(read_shape(v));
  if (P.volume.empty()) t.fail("volume", "at least one [[volume]] table is required");
  bool any_endpoints = false;
  for (const Shape& s : P.volume) any_endpoints |= s.endpoints;
  if (!any_endpoints) t.fail("volume", "no [[volume]] may hold endpoints (all have endpoints = false)");
  for (const TomlTable& l : t.tables("level")) {
    l.check_keys({"b", "alpha", "rotate", "direction", "around_all"});
    MigLevel L;
    L.branching = int(l.integer("b", 0, 100000));
    L.alpha = float(l.number("alpha", 54.0, 1.0, 180.0)) * kPi / 180.0f;
    L.rotate = float(l.number("rotate", 0.0, -180.0, 180.0)) * kPi / 180.0f;
    if (l.has("direction")) {
      glm::vec3 dir = l.vec3("direction", -1.0, 1.0);
      if (glm::length(dir) < 1e-3f) l.fail("direction", "must not be the zero vector");
      L.direction = dir;
    }
    L.around_all = l.boolean("around_all", false);
    if (P.levels.empty())
      for (const char* key : {"alpha", "rotate", "direction", "around_all"})
        if (l.has(key)) l.fail(key, "level 1 is the user's [[volume]]; this key applies to later levels");
    P.levels.push_back(L);
  }
  if (P.levels.empty()) t.fail("level", "at least one [[level]] table is required");
  if (P.levels.size() > 12) t.fail("level", "at most 12 levels");
  // Refuse runaway trees before building them: predicted endpoints and graph nodes.
  double endpoints = P.levels[0].branching, total = endpoints, nodes = double(P.nodes);
  for (size_t i = 1; i < P.levels.size(); ++i) {
    double around = P.levels[i].around_all ? total : endpoints;
    nodes += around * double(P.subgraph_nodes);
    endpoints = around * P.levels[i].branching;
    total += endpoints;
  }
  if (total > kMaxMigEndpoints)
    t.fail("level", "would create about " + std::to_string(int64_t(total)) + " endpoints, more than " +
                        std::to_string(int64_t(kMaxMigEndpoints)));
  if (nodes > kMaxMigGraphNodes)
    t.fail("subgraph_nodes", "would build about " + std::to_string(int64_t(nodes)) +
                                 " graph nodes, more than " + std::to_string(int64_t(kMaxMigGraphNodes)));
  return P;
}

// The method's own species keys; the registry adds the common and the look keys.
constexpr std::string_view kKeys[] = {
    "nodes", "spacing", "reach", "root", "shell", "subgraph_nodes", "subgraph_radius", "shrink",
    "trunk_height", "trunk_sources", "volume", "level", FOREST_SKELETON_STYLE_KEYS};

Skeleton skeleton_pass(const TomlTable& t, uint64_t seed) {
  MigParams P = read_params(t);
  SkeletonStyle defaults;
  defaults.simplify = 0.05f;
  SkeletonStyle style = read_skeleton_style(t, defaults);
  MigStats stats;
  TreeGraph graph = grow_mig(P, seed, &stats);
  if (graph.nodes.size() < 2) t.fail("volume", "no endpoint could be joined to the root");
  Skeleton out{finish_skeleton(std::move(graph), style)};
  out.meta["graph_nodes"] = stats.graph_nodes;
  out.meta["subgraphs"] = stats.subgraphs;
  out.meta["endpoints"] = stats.endpoints;
  out.meta["unreachable_candidates"] = stats.unreachable;
  return out;
}

// The built-in preset: the text of scenes/species/mig_o.toml.
const char* builtin_preset() {
  // Keep identical to scenes/species/mig_o.toml (a unit test compares them).
  return R"toml(method = "mig"
# Seed 001 Table 4.1 (o): "cylinder and portion of sphere with alpha = 0.7 pi, b = 11;
# levels 2, 3: alpha = 0.45 pi, b = 6" -- a straight, tall trunk under a spherical crown.
# The thesis gives no sizes (d, K, k, r); these are ours, for a ~11 m tree. Forest budget (levels 1-2 only).
name = "mig_o"
seed = 7
nodes = 2500            # K, level-1 graph
reach = 4.0             # longest Yao edge, in node spacings
shell = 1.2             # d_e: endpoints within 1.2 m of the crown surface
subgraph_nodes = 120    # k
subgraph_radius = 2.2   # r at level 2 (m)
shrink = 0.6            # a
simplify = 0.15         # m, Douglas-Peucker on branch chains
smooth = 6
trunk_radius = 0.22
tip_radius = 0.008
zeta = 0.3
ring_sides_min = 3
ring_sides_max = 8
# foliage: a method demo: the shared foliage model, blade 6-10 cm on shoots of 25-35 cm.
leaf_shape = "ovate"
foliage = "shoots"
leaf_size = 0.08
leaf_size_jitter = 0.2
leaf_phyllotaxis = "alternate"
leaves_per_shoot = 6
shoot_length = 0.3
shoot_spacing = 0.1
foliage_depth = 2.0
shoot_angle = 50
leaf_angle = 55
shoots_per_tip = 3
shoots_per_spray = 3
leaf_color_jitter = 0.1
autumn_color = [0.55, 0.34, 0.05]
bark_color = [0.27, 0.21, 0.16]
leaf_color = [0.16, 0.33, 0.08]

[[volume]]              # the trunk: paths squeeze through it into one stem
shape = "cylinder"
center = [0.0, 0.0, 0.0]
radius = 0.5
height = 5.0

[[volume]]              # portion of sphere, alpha = 0.7 pi = 126 deg
shape = "sphere_portion"
center = [0.0, 4.5, 0.0]
radius = 4.0
angle = 126.0

[[level]]
b = 11

[[level]]
b = 6
alpha = 81.0            # 0.45 pi

# level 3 (b = 6) of the table is left out: 66 instead of 396 endpoints keeps the forest
# budget; mig_a_hero shows a full four-level tree.
)toml";
}

}  // namespace

constinit const MethodEntry kMigMethod{"mig", kKeys, skeleton_pass, builtin_preset, nullptr};

}  // namespace forest
