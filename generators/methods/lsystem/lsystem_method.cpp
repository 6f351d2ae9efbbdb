// Species keys of method "lsystem" (all optional unless marked; ranges are checked):
//   name, seed (0..2^53), iterations (required, 0..12), axiom (required; see lsystem.h for
//   the alphabet), angle / angle_jitter / roll_jitter (degrees), step (m) / step_jitter
//   (fraction) / length_scale (factor of '!'), tropism ([x, y, z]) / tropism_strength,
//   tip_radius (m) / pipe_exponent (pipe model: 2 da Vinci, 2.49 Murray, 3), leaf_size (m,
//   0 = no leaves) / leaf_size_jitter / leaf_angle / leaf_angle_jitter (deg) / leaves_per_tip
//   (tip cluster) / leaves_along (leaf nodes per twig segment) / phyllotaxis ("alternate" or
//   "distichous", "opposite" or "decussate", "whorled", "spiral") / leaves_per_node (whorled
//   only, >= 3) / divergence_angle (deg, spiral only) /
//   leaf_color_jitter (per-leaf color variation), and [[production]] tables
//   { predecessor = "X" (one letter), successor = "...", weight = 1.0 }; plus the shared
//   look keys (model/look_keys.h).
#include "generators/methods/lsystem/lsystem_method.h"
#include "generators/core/limits.h"

#include <cmath>
#include <vector>

#include "generators/core/toml_reader.h"
#include "generators/tree/leaves.h"
#include "generators/methods/lsystem/lsystem.h"
#include "generators/tree/pipe_model.h"

namespace forest {

namespace {

// Limits that keep a typo from exhausting the machine; generous for real plants.

struct LSystemSpecies {
  int iterations = 0;
  LSystem system;
  TurtleParams turtle;
  float tip_radius = 0.002f;
  float pipe_exponent = 2.0f;
  LeafParams leaves;
};

void check_syntax(const TomlTable& t, std::string_view key, const std::string& s) {
  if (auto err = check_lsystem_syntax(s)) t.fail(key, *err);
}

LSystemSpecies read_species(const TomlTable& t) {
  LSystemSpecies s;
  s.iterations = int(t.integer("iterations", 0, kMaxLSystemIterations));  // required
  s.system.axiom = t.string("axiom");
  if (s.system.axiom.empty()) t.fail("axiom", "must not be empty");
  check_syntax(t, "axiom", s.system.axiom);

  TurtleParams& p = s.turtle;
  p.angle_deg = float(t.number("angle", 22.5, -360.0, 360.0));
  p.angle_jitter_deg = float(t.number("angle_jitter", 0.0, 0.0, 180.0));
  p.roll_jitter_deg = float(t.number("roll_jitter", 0.0, 0.0, 180.0));
  p.step = float(t.number("step", 1.0, 1e-4, 100.0));
  p.step_jitter = float(t.number("step_jitter", 0.0, 0.0, 0.9));
  p.length_scale = float(t.number("length_scale", 0.9, 0.01, 10.0));
  p.tropism = t.vec3("tropism", glm::vec3(0.0f, -1.0f, 0.0f), -1.0, 1.0);
  p.tropism_strength = float(t.number("tropism_strength", 0.0, -1.0, 1.0));
  if (p.tropism_strength != 0.0f && glm::length(p.tropism) < 1e-3f)
    t.fail("tropism", "must not be the zero vector when tropism_strength is set");
  s.tip_radius = float(t.number("tip_radius", 0.002, 1e-5, 1.0));
  s.pipe_exponent = float(t.number("pipe_exponent", 2.0, 1.0, 4.0));

  LeafParams& l = s.leaves;
  l.size = float(t.number("leaf_size", 0.1, 0.0, 10.0));
  l.size_jitter = float(t.number("leaf_size_jitter", 0.0, 0.0, 0.9));
  l.angle_deg = float(t.number("leaf_angle", 40.0, 0.0, 180.0));
  l.angle_jitter_deg = float(t.number("leaf_angle_jitter", 10.0, 0.0, 90.0));
  l.per_tip = int(t.integer("leaves_per_tip", 1, 0, 16));
  l.along = int(t.integer("leaves_along", 0, 0, 16));
  l.phyllotaxis = *parse_phyllotaxis(
      t.choice("phyllotaxis", "spiral", {"alternate", "distichous", "opposite", "decussate", "whorled", "spiral"}));
  if (l.phyllotaxis == Phyllotaxis::whorled) {
    l.per_node = int(t.integer("leaves_per_node", 3, 3, 16));
  } else if (t.has("leaves_per_node")) {
    int implied = leaves_at_node(l.phyllotaxis, 0);
    if (t.integer("leaves_per_node", implied, 1, 16) != implied)
      t.fail("leaves_per_node", std::string("must be ") + std::to_string(implied) + " for phyllotaxis \"" +
                                    phyllotaxis_name(l.phyllotaxis) + "\" (only whorled leaves choose their count)");
  }
  l.divergence_deg = float(t.number("divergence_angle", 137.5, 0.0, 360.0));
  if (t.has("divergence_angle") && l.phyllotaxis != Phyllotaxis::spiral)
    t.fail("divergence_angle", "applies to phyllotaxis \"spiral\" only");
  l.color_jitter = float(t.number("leaf_color_jitter", 0.0, 0.0, 0.5));
  p.leaf_angle_deg = l.angle_deg;
  p.leaf_size = l.size;
  p.leaf_size_jitter = l.size_jitter;
  p.leaf_color_jitter = l.color_jitter;

  for (const TomlTable& pt : t.tables("production")) {
    pt.check_keys({"predecessor", "successor", "weight"});
    Production prod;
    std::string pred = pt.string("predecessor");
    if (pred.size() != 1 || !((pred[0] >= 'A' && pred[0] <= 'Z') || (pred[0] >= 'a' && pred[0] <= 'z')))
      pt.fail("predecessor", "must be a single letter, got '" + pred + "'");
    prod.predecessor = pred[0];
    prod.successor = pt.string("successor");
    check_syntax(pt, "successor", prod.successor);
    prod.weight = pt.number("weight", 1.0, 1e-9, 1e9);
    s.system.productions.push_back(prod);
  }
  return s;
}

bool uses_leaf_symbols(const LSystem& system) {
  if (system.axiom.find('L') != std::string::npos) return true;
  for (const Production& p : system.productions)
    if (p.successor.find('L') != std::string::npos) return true;
  return false;
}

// The method's own species keys; the registry adds the common and the look keys.
constexpr std::string_view kKeys[] = {
    "iterations", "axiom", "angle", "angle_jitter", "roll_jitter", "step", "step_jitter",
    "length_scale", "tip_radius", "pipe_exponent", "tropism", "tropism_strength", "leaf_size",
    "leaf_size_jitter", "leaf_angle", "leaf_angle_jitter", "leaves_per_tip", "leaves_along",
    "phyllotaxis", "leaves_per_node", "divergence_angle", "leaf_color_jitter", "production"};

Skeleton skeleton_pass(const TomlTable& root, uint64_t seed) {
  LSystemSpecies s = read_species(root);

  std::string symbols;
  try {
    symbols = rewrite(s.system, s.iterations, seed);
  } catch (const InputError& e) {
    root.fail("iterations", e.what());  // explosion guard: name the key to change
  }
  TreeGraph graph = interpret(symbols, s.turtle, seed);
  assign_pipe_radii(graph, s.tip_radius, s.pipe_exponent);
  // Leaves: where the author put L symbols, else on the terminal twigs.
  if (!uses_leaf_symbols(s.system) && s.leaves.size > 0.0f) {
    // Refuse absurd leaf counts before allocating them (an upper bound: tips and others).
    size_t tips = graph.nodes.size();
    std::vector<char> has_child(graph.nodes.size(), 0);
    for (const TreeNode& n : graph.nodes)
      if (n.parent >= 0) has_child[size_t(n.parent)] = 1;
    for (char c : has_child) tips -= size_t(c);
    size_t bound = tips * size_t(s.leaves.per_tip) +
                   graph.nodes.size() * size_t(s.leaves.along) *
                       size_t(leaves_at_node(s.leaves.phyllotaxis, s.leaves.per_node));
    if (bound > kMaxLeavesPerModel)
      root.fail(root.has("leaves_along") ? "leaves_along" : "leaves_per_tip",
                "could give up to " + std::to_string(bound) + " leaves, more than " +
                    std::to_string(kMaxLeavesPerModel));
    place_twig_leaves(graph, s.leaves, seed);
  }
  if (s.leaves.size <= 0.0f) graph.leaves.clear();
  if (graph.leaves.size() > kMaxLeavesPerModel)
    root.fail(root.has("leaves_along") ? "leaves_along" : "leaves_per_tip",
              "gives " + std::to_string(graph.leaves.size()) + " leaves, more than " +
                  std::to_string(kMaxLeavesPerModel));
  return {std::move(graph)};
}

// The built-in preset: the text of scenes/species/fig2_1.toml.
const char* builtin_preset() {
  // Keep identical to scenes/species/fig2_1.toml (a unit test compares them).
  return R"toml(method = "lsystem"
# Seed 000, Fig. 2.1 (c): a bracketed L-system plant (after ABOP Fig. 1.24 f).
#   n = 7, delta = 22.5 deg, axiom X, X -> F[[X]-X]F[+FX]-X, F -> FF.
# The dissertation's OCR printed the brackets as ( ) and cuts the X production off after
# "F[+FX]"; we restore the trailing "-X" (as in ABOP 1.24 f): without it the main axis would
# stop after its second F and the plant would be lopsided and a third smaller.
# The figure is planar; a random roll at every branch start makes it a 3D plant.
name = "fig2_1"
seed = 1
iterations = 7
axiom = "X"
angle = 22.5          # degrees
angle_jitter = 4.0    # degrees, per turn
roll_jitter = 180.0   # degrees, random roll about the heading at every '['
step = 0.012          # meters per F (128 F per first-level segment after 7 iterations)
step_jitter = 0.1
tip_radius = 0.0015   # meters
pipe_exponent = 2.0   # da Vinci
leaf_size = 0.05
leaf_size_jitter = 0.25
leaf_angle = 35.0
leaf_shape = "elliptic"
leaf_color_jitter = 0.1
leaves_per_tip = 1
bark_color = [0.22, 0.16, 0.10]
leaf_color = [0.14, 0.32, 0.06]

[[production]]
predecessor = "X"
successor = "F[[X]-X]F[+FX]-X"

[[production]]
predecessor = "F"
successor = "FF"
)toml";
}

}  // namespace

constinit const MethodEntry kLsystemMethod{"lsystem", kKeys, skeleton_pass, builtin_preset,
                                           nullptr};

}  // namespace forest
