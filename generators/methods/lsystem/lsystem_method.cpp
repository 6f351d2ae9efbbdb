// Species keys of method "lsystem" (all optional unless marked; ranges are checked):
//   name, seed (0..2^53), iterations (required, 0..12), axiom (required; see lsystem.h for
//   the alphabet), angle / angle_jitter / roll_jitter (degrees), step (m) / step_jitter
//   (fraction) / length_scale (factor of '!'), tropism ([x, y, z]) / tropism_strength,
//   tip_radius (m) / pipe_exponent (pipe model: 2 da Vinci, 2.49 Murray, 3), and
//   [[production]] tables { predecessor = "X" (one letter), successor = "...", weight = 1.0 };
//   plus the shared look keys (model/look_keys.h) and foliage keys (tree/foliage.h). An 'L'
//   in the grammar places a foliage element there instead of the foliage stage's placement.
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

  // An 'L' places one foliage element; the shared foliage stage sizes and colours it.
  p.leaf_angle_deg = 45.0f;
  p.leaf_size = 1.0f;
  p.leaf_size_jitter = 0.0f;
  p.leaf_color_jitter = 0.0f;

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
    "length_scale", "tip_radius", "pipe_exponent", "tropism", "tropism_strength", "production"};

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
  // Foliage: where the author put L symbols (the foliage stage sizes them), else the shared
  // foliage stage places it.
  Skeleton out{std::move(graph)};
  out.own_leaves = uses_leaf_symbols(s.system);
  if (!out.own_leaves) out.graph.leaves.clear();
  if (out.graph.leaves.size() > kMaxLeavesPerModel)
    root.fail("iterations", "gives " + std::to_string(out.graph.leaves.size()) + " L symbols, more than " +
                                std::to_string(kMaxLeavesPerModel));
  return out;
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
# foliage: ABOP's plant carries one leaf at every tip (blade 4-6 cm); single leaves, no young-wood
# foliage: foliage (foliage_depth = 0).
leaf_shape = "elliptic"
foliage = "leaves"
leaf_size = 0.05
leaf_size_jitter = 0.25
leaf_phyllotaxis = "alternate"
shoot_spacing = 1.0
foliage_depth = 0.0
shoot_angle = 35
shoot_angle_jitter = 10
leaf_angle = 55
shoots_per_tip = 1
shoots_per_spray = 1
leaf_color_jitter = 0.1
autumn_color = [0.55, 0.34, 0.05]
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
