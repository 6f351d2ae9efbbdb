// Species keys of method "magnetic" (all optional; ranges are checked):
//   name, seed, mode ("2d" | "3d"), size ([x, y, z] simulation units), domain ("box" |
//   "dome" [ours]: the half ellipsoid in the box, a rounded crown), cell, dt, speed, mass,
//   profile ("spiral" | "power" | "triangle" | "square" | "constant"), q0, trunk_q0 (the
//   first particle's q0), amplitude, mean,
//   period, field (B0), field_noise (0..1), noise_scale, field_tilt (3d), child_spacing,
//   trunk_clear ([ours]: arc length up the trunk before its first child, default
//   child_spacing),
//   max_curves, max_depth, scale (m per unit), [[spiral]] tables { T, alpha } from the
//   largest to the smallest (default: the thesis' (650, 0.8) (450, 0.75) (250, 0.7)
//   (50, 0.65)); plus the skeleton style keys of graph_skeleton.h.
#include "generators/methods/magnetic/magnetic_method.h"

#include "generators/methods/common/graph_skeleton.h"

namespace forest {

MagneticSpecies read_magnetic_species(const TomlTable& t) {
  MagneticSpecies s;
  SpaceFillParams& P = s.fill;
  s.field.three_d = t.choice("mode", "2d", {"2d", "3d"}) == "3d";
  glm::vec3 size = t.vec3("size", glm::vec3(600.0f, 800.0f, 600.0f), 1.0, 100000.0);
  P.size = glm::dvec3(size);
  P.domain = t.choice("domain", "box", {"box", "dome"}) == "dome" ? Domain::Dome : Domain::Box;
  P.cell = t.number("cell", 4.0, 0.01, 10000.0);
  P.dt = t.number("dt", 0.5, 1e-3, 100.0);
  P.speed = t.number("speed", 1.0, 1e-3, 1000.0);
  if (P.dt * P.speed > 0.5 * P.cell)
    t.fail("dt", "a step (dt * speed) must not exceed half a cell, or curves could jump cells");
  P.mass = t.number("mass", 1.0, 1e-6, 1e6);
  std::string profile = t.choice("profile", "spiral", {"spiral", "power", "triangle", "square", "constant"});
  P.charge.profile = profile == "power"      ? ChargeProfile::Power
                     : profile == "triangle" ? ChargeProfile::Triangle
                     : profile == "square"   ? ChargeProfile::Square
                     : profile == "constant" ? ChargeProfile::Constant
                                             : ChargeProfile::Spiral;
  P.charge.q0 = t.number("q0", 1.0, -1e6, 1e6);
  P.trunk_q0 = t.number("trunk_q0", P.charge.q0, -1e6, 1e6);
  P.charge.amplitude = t.number("amplitude", 1.0, 0.0, 1e6);
  P.charge.mean = t.number("mean", 0.5, -1e6, 1e6);
  P.charge.period = t.number("period", 100.0, 1e-3, 1e9);
  s.field.b0 = t.number("field", 1.0, -1e6, 1e6);
  s.field.noise = t.number("field_noise", 0.0, 0.0, 1.0);
  s.field.noise_scale = t.number("noise_scale", 50.0, 1e-3, 1e9);
  s.field.tilt = t.number("field_tilt", 0.3, -100.0, 100.0);
  if (!s.field.three_d && t.has("field_tilt")) t.fail("field_tilt", "applies to mode = \"3d\" only");
  P.child_spacing = t.number("child_spacing", 60.0, 0.1, 1e9);
  P.trunk_clear = t.number("trunk_clear", P.child_spacing, 0.1, 1e9);
  P.max_curves = int(t.integer("max_curves", 300, 1, 20000));
  P.max_depth = int(t.integer("max_depth", 6, 0, 64));
  s.scale = t.number("scale", 0.015, 1e-6, 1000.0);
  std::vector<TomlTable> spirals = t.tables("spiral");
  if (!spirals.empty()) P.pairs.clear();
  for (const TomlTable& sp : spirals) {
    sp.check_keys({"T", "alpha"});
    SpiralPair pair;
    pair.T = sp.number("T", 1.0, 1e6);
    pair.alpha = sp.number("alpha", 0.0, 5.0);
    if (!P.pairs.empty() && pair.T > P.pairs.back().T)
      sp.fail("T", "[[spiral]] pairs go from the largest T to the smallest");
    P.pairs.push_back(pair);
  }
  // Bound the work: curves × steps per curve.
  double steps = double(P.max_curves) * (P.pairs.front().T / P.dt);
  if (steps > 5e7) t.fail("max_curves", "max_curves * T / dt is " + std::to_string(int64_t(steps)) +
                                            " steps, more than 5e7");
  return s;
}

TreeGraph magnetic_tree(const MagneticResult& r, const MagneticSpecies& s) {
  TreeGraph g;
  const bool three_d = s.field.three_d;
  const glm::dvec3 origin(0.5 * s.fill.size.x, 0.0, three_d ? 0.5 * s.fill.size.z : 0.0);
  auto to_model = [&](glm::dvec3 p) { return glm::vec3((p - origin) * s.scale); };
  // node_of[c][k]: tree node of point k of curve c. A child's point 0 IS its parent's release
  // point, so it shares that node.
  std::vector<std::vector<uint32_t>> node_of(r.curves.size());
  for (size_t c = 0; c < r.curves.size(); ++c) {
    const MagneticCurve& curve = r.curves[c];
    std::vector<uint32_t>& ids = node_of[c];
    ids.resize(curve.points.size());
    if (curve.parent >= 0) {
      ids[0] = node_of[size_t(curve.parent)][curve.parent_point];
    } else {
      TreeNode root;
      root.position = to_model(curve.points[0]);
      ids[0] = uint32_t(g.nodes.size());
      g.nodes.push_back(root);
    }
    for (size_t k = 1; k < curve.points.size(); ++k) {
      TreeNode node;
      node.position = to_model(curve.points[k]);
      node.parent = int32_t(ids[k - 1]);
      node.order = curve.depth;
      ids[k] = uint32_t(g.nodes.size());
      g.nodes.push_back(node);
    }
  }
  return g;
}

std::string magnetic_svg_from_species_text(const std::string& text, const std::string& name,
                                           std::optional<uint64_t> seed) {
  TomlDocument doc = TomlDocument::parse(text, name);
  TomlTable t = doc.root();
  if (t.string("method") != "magnetic") t.fail("method", "--svg needs a species of method \"magnetic\"");
  uint64_t sd = seed.value_or(uint64_t(t.integer("seed", 1, 0, int64_t(1) << 53)));
  MagneticSpecies s = read_magnetic_species(t);
  if (s.field.three_d) t.fail("mode", "--svg needs mode = \"2d\": the 3D variant has no planar curves");
  s.field.seed = sd;
  MagneticResult r = grow_magnetic(s.fill, s.field, sd);
  return magnetic_svg(r, glm::dvec2(s.fill.size.x, s.fill.size.y));
}

namespace {

// The method's own species keys; the registry adds the common and the look keys.
constexpr std::string_view kKeys[] = {
    "mode", "size", "domain", "cell", "dt", "speed", "mass", "profile", "q0", "trunk_q0", "amplitude",
    "mean", "period", "field", "field_noise", "noise_scale", "field_tilt", "child_spacing", "trunk_clear",
    "max_curves", "max_depth", "scale", "spiral", FOREST_SKELETON_STYLE_KEYS};

Skeleton skeleton_pass(const TomlTable& t, uint64_t seed) {
  MagneticSpecies s = read_magnetic_species(t);
  s.field.seed = seed;
  SkeletonStyle defaults;
  defaults.simplify = 0.01f;
  defaults.smooth_iterations = 0;
  defaults.trunk_radius = 0.12f;
  defaults.tip_radius = 0.003f;
  SkeletonStyle style = read_skeleton_style(t, defaults);
  MagneticResult r = grow_magnetic(s.fill, s.field, seed);
  TreeGraph graph = magnetic_tree(r, s);
  if (graph.nodes.size() < 2) t.fail("size", "the first particle left the domain at once");
  Skeleton out{finish_skeleton(std::move(graph), style)};
  out.meta["curves"] = r.curves.size();
  return out;
}

// The built-in preset: the text of scenes/species/magnetic_klimt.toml.
const char* builtin_preset() {
  // Keep identical to scenes/species/magnetic_klimt.toml (a unit test compares them).
  return R"toml(method = "magnetic"
# Seed 001 ch7, Fig. 7.7: a Klimt-style tree of space-filling magnetic curves, as a planar
# relief model (tubes in the x-y plane). Spiral charge q(t) = (T - t)^-alpha with the four
# (T, alpha) pairs of Fig. 7.3's diagonal, tried from the largest; a curve that would enter
# a cell owned by another curve (not itself or its parent) restarts with the next smaller
# pair. Table 7.1's stylized tree has 72 curves; 600 x 800 units = 9 x 12 m. HERO model
# (decorative relief, ~26 K branch triangles: the spirals need many rings).
name = "magnetic_klimt"
seed = 5
mode = "2d"
size = [600.0, 800.0, 1.0]  # z unused in 2d
cell = 4.0
dt = 0.5
q0 = 1.0
trunk_q0 = 0.25      # a straighter main curve: it starts wider, spirals at its end
field = 1.0
child_spacing = 70.0
max_curves = 72
max_depth = 5
scale = 0.015          # m per unit
simplify = 0.012
trunk_radius = 0.14
tip_radius = 0.004
zeta = 0.35
ring_sides_min = 3
ring_sides_max = 6
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
bark_color = [0.45, 0.33, 0.12]
leaf_color = [0.55, 0.45, 0.10]

[[spiral]]
T = 650.0
alpha = 0.8
[[spiral]]
T = 450.0
alpha = 0.75
[[spiral]]
T = 250.0
alpha = 0.7
[[spiral]]
T = 50.0
alpha = 0.65
)toml";
}

}  // namespace

constinit const MethodEntry kMagneticMethod{"magnetic", kKeys, skeleton_pass, builtin_preset,
                                            nullptr};

}  // namespace forest
