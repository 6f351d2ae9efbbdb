// Species keys of method "mgv" (all optional unless marked; ranges are checked):
//   name, seed, size ([x, y, z] m: the graph box, root at its bottom centre), nodes, reach,
//   [[iteration]] tables (required, in order): select = "point" | "volume" | "hops",
//   point ([x, y, z]), endpoints, hops (k), outer (t), rule = "piecewise" | "axis" |
//   "height", alpha (deg, constant) or alpha1 / alpha2 (deg) / h0, alpha1_min / alpha1_max
//   (deg, random α1 per source node), theta (deg, rule "axis"), policy = "any" | "hanging" |
//   "upright", sources_above (m: only tree nodes this high start the iteration's paths), and
//   [[iteration.volume]] tables (select = "volume"; see graph_volume.h);
//   plus the skeleton style keys of graph_skeleton.h.
#include "generators/methods/mgv/mgv_method.h"
#include "generators/core/limits.h"

#include "generators/methods/common/graph_skeleton.h"

namespace forest {

namespace {
constexpr float kDeg = 3.14159265358979323846f / 180.0f;

MgvIteration read_iteration(const TomlTable& t, size_t index) {
  t.check_keys({"select", "point", "endpoints", "hops", "outer", "rule", "alpha", "alpha1", "alpha2",
                "h0", "alpha1_min", "alpha1_max", "theta", "policy", "sources_above", "volume"});
  MgvIteration I;
  std::string select = t.choice("select", index == 0 ? "point" : "hops", {"point", "volume", "hops"});
  I.select = select == "point" ? EndpointSelect::Point
             : select == "volume" ? EndpointSelect::Volume
                                  : EndpointSelect::Hops;
  I.point = t.vec3("point", glm::vec3(0.0f, 4.0f, 0.0f), -1000.0, 1000.0);
  I.endpoints = size_t(t.integer("endpoints", I.select == EndpointSelect::Point ? 1 : 100, 1, kMaxMgvEndpoints));
  I.hops = uint32_t(t.integer("hops", 4, 1, 1000));
  I.outer = float(t.number("outer", 0.6, 0.01, 1.0));
  std::string rule = t.choice("rule", "piecewise", {"piecewise", "axis", "height"});
  I.rule = rule == "axis" ? AlphaRule::Axis : rule == "height" ? AlphaRule::Height : AlphaRule::Piecewise;
  if (t.has("alpha") && (t.has("alpha1") || t.has("alpha2") || t.has("h0")))
    t.fail("alpha", "give either alpha (constant) or alpha1 / alpha2 / h0, not both");
  if (t.has("alpha")) {
    I.alpha1 = I.alpha2 = float(t.number("alpha", -180.0, 180.0)) * kDeg;
  } else {
    I.alpha1 = float(t.number("alpha1", 0.0, -180.0, 180.0)) * kDeg;
    I.alpha2 = float(t.number("alpha2", 0.0, -180.0, 180.0)) * kDeg;
  }
  I.h0 = uint32_t(t.integer("h0", 1, 0, 100000));
  if (t.has("alpha1_min") || t.has("alpha1_max")) {
    if (t.has("alpha1") || t.has("alpha")) t.fail("alpha1_min", "a random alpha1 replaces alpha / alpha1");
    I.alpha1_random = true;
    I.alpha1_lo = float(t.number("alpha1_min", -180.0, 180.0)) * kDeg;
    I.alpha1_hi = float(t.number("alpha1_max", -180.0, 180.0)) * kDeg;
    if (I.alpha1_hi < I.alpha1_lo) t.fail("alpha1_max", "must be >= alpha1_min");
  }
  I.theta = float(t.number("theta", 25.0, -180.0, 180.0)) * kDeg;
  if (t.has("theta") && I.rule != AlphaRule::Axis) t.fail("theta", "applies to rule = \"axis\" only");
  std::string policy = t.choice("policy", "any", {"any", "hanging", "upright"});
  I.policy = policy == "hanging" ? EndpointPolicy::Hanging
             : policy == "upright" ? EndpointPolicy::Upright
                                   : EndpointPolicy::Any;
  if (t.has("sources_above")) I.sources_above = float(t.number("sources_above", 0.0, 1000.0));
  for (const TomlTable& v : t.tables("volume")) I.volume.push_back(read_shape(v));
  if (I.select == EndpointSelect::Volume && I.volume.empty())
    t.fail("volume", "select = \"volume\" needs at least one [[iteration.volume]] table");
  if (I.select != EndpointSelect::Volume && !I.volume.empty())
    t.fail("volume", "only select = \"volume\" uses a volume");
  return I;
}

}  // namespace

MgvParams read_mgv_params(const TomlTable& t) {
  MgvParams P;
  P.size = t.vec3("size", glm::vec3(10.0f, 12.0f, 10.0f), 0.1, 1000.0);
  P.nodes = size_t(t.integer("nodes", 30000, 100, kMaxMgvNodes));
  P.reach = float(t.number("reach", 4.0, 1.5, 20.0));
  size_t i = 0;
  for (const TomlTable& it : t.tables("iteration")) P.iterations.push_back(read_iteration(it, i++));
  if (P.iterations.empty()) t.fail("iteration", "at least one [[iteration]] table is required");
  if (P.iterations.size() > 16) t.fail("iteration", "at most 16 iterations");
  return P;
}

namespace {

// The method's own species keys; the registry adds the common and the look keys.
constexpr std::string_view kKeys[] = {
    "size", "nodes", "reach", "iteration", FOREST_SKELETON_STYLE_KEYS};

Skeleton skeleton_pass(const TomlTable& t, uint64_t seed) {
  MgvParams P = read_mgv_params(t);
  SkeletonStyle defaults;
  defaults.simplify = 0.05f;
  SkeletonStyle style = read_skeleton_style(t, defaults);
  MgvGraph graph = build_mgv_graph(P, seed);
  MgvStats stats;
  TreeGraph tree = grow_mgv(graph, P, seed, &stats);
  if (tree.nodes.size() < 2) t.fail("iteration", "no endpoint could be joined to the root");
  Skeleton out{finish_skeleton(std::move(tree), style)};
  out.meta["graph_nodes"] = graph.graph.size();
  out.meta["endpoints"] = stats.endpoints;
  return out;
}

// The built-in preset: the text of scenes/species/mgv_c.toml.
const char* builtin_preset() {
  // Keep identical to scenes/species/mgv_c.toml (a unit test compares them).
  return R"toml(method = "mgv"
# Seed 001 Table 6.1 (c), the ash of Fig. 5.5 (c) / 6.6: iteration 1 is the trunk (one
# endpoint, alpha = 0); iteration 2 puts Poisson endpoints in a half-ellipsoid crown with
# alpha1 = 90, alpha2 = 0, h0 = 1 (branches leave the trunk sideways, then run straight);
# iterations 3-4 use the default alpha1 = 30, alpha2 = 0, h0 = 1 with endpoints k hops
# from the tree, outermost fraction t = 0.6. Sizes and counts are ours (forest budget:
# ~85 endpoints; the thesis used 150 K nodes and 4-8 K endpoints).
name = "mgv_c"
seed = 3
size = [10.0, 12.0, 10.0]   # graph box (m), root at the bottom centre
nodes = 30000
simplify = 0.15
smooth = 6
trunk_radius = 0.2
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
bark_color = [0.30, 0.25, 0.20]
leaf_color = [0.17, 0.34, 0.09]

[[iteration]]               # the trunk
select = "point"
point = [0.0, 4.5, 0.0]
alpha = 0.0

[[iteration]]               # primary branches into the crown
select = "volume"
endpoints = 14
alpha1 = 90.0
alpha2 = 0.0
h0 = 1
[[iteration.volume]]
shape = "half_ellipsoid"
center = [0.0, 3.5, 0.0]
radii = [4.0, 7.5, 4.0]

[[iteration]]
select = "hops"
endpoints = 32
hops = 6
outer = 0.6
alpha1 = 30.0
alpha2 = 0.0
h0 = 1

[[iteration]]
select = "hops"
endpoints = 40
hops = 4
outer = 0.6
alpha1 = 30.0
alpha2 = 0.0
h0 = 1
)toml";
}

}  // namespace

constinit const MethodEntry kMgvMethod{"mgv", kKeys, skeleton_pass, builtin_preset, nullptr};

}  // namespace forest
