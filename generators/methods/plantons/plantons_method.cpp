// Species keys of method "plantons" (all optional unless marked; ranges are checked):
//   name, seed, model (learned model file, relative to the preset) or ground_truth (number of
//   ground-truth trees to learn from in-process; exactly one of the two), max_organs,
//   max_depth, segments (nodes per stem), min_radius (m); plus the shared look keys
//   (model/look_keys.h) and foliage keys (tree/foliage.h).
#include "generators/methods/plantons/plantons_method.h"

#include "generators/core/toml_reader.h"
#include "generators/methods/plantons/plantons_learn.h"
#include "generators/methods/plantons/plantons_samples.h"
#include "generators/methods/plantons/plantons_synth.h"

namespace forest {

namespace {

// The method's own species keys; the registry adds the common and the look keys.
constexpr std::string_view kKeys[] = {
    "model", "ground_truth", "max_organs", "max_depth", "segments", "min_radius"};

Skeleton skeleton_pass(const TomlTable& t, uint64_t seed) {
  if (t.has("model") == t.has("ground_truth"))
    t.fail(t.has("model") ? "ground_truth" : "model", "give exactly one of `model` (a learned model file) and `ground_truth`");
  PlantonModel model;
  std::string source;
  if (t.has("model")) {
    model = load_model(t.existing_file("model"));
    source = t.string("model");
  } else {
    size_t trees = size_t(t.integer("ground_truth", 1, 64));
    LearnParams lp;
    lp.initial_plantons = {3, 1};
    model = learn_plantons(ground_truth_samples(trees, 1), lp).model;
    source = "ground truth (" + std::to_string(trees) + " trees, learned in-process)";
  }
  SynthesisParams sp;
  sp.max_organs = size_t(t.integer("max_organs", 20000, 1, 500000));
  sp.max_depth = uint32_t(t.integer("max_depth", 12, 0, 64));
  OrganMeshing om;
  om.segments = int(t.integer("segments", 6, 1, 64));
  om.min_radius = float(t.number("min_radius", 0.002, 1e-5, 1.0));

  SynthesizedTree s = synthesize_plantons(model, sp, seed);
  // The learned leaf organs shaped the synthesis; the model's foliage is the shared stage's.
  Skeleton out{graph_from_organs(s.tree, om)};
  out.graph.leaves.clear();
  size_t stems = 0;
  for (const Organ& o : s.tree.organs) stems += o.type == OrganType::Stem;
  out.meta["plantons"] = model.N();
  out.meta["organ_count"] = s.tree.organs.size();
  out.meta["stem_count"] = stems;
  out.meta["capped"] = s.capped;
  out.meta["model_source"] = source;
  return out;
}

// The built-in preset: learns from three ground-truth trees in-process, then synthesizes.
const char* builtin_preset() {
  return R"toml(method = "plantons"
# Seed 004 (Wang et al. 2006) on the reference note's synthetic ground truth: plantons T
# (trunk), P, S (branches) and L (leaves) are learned in-process from three ground-truth
# trees, then a new tree is synthesized. Presets normally name a model written by
# `forest learn` instead (see scenes/species/plantons_*.toml).
name = "plantons_ground_truth"
seed = 3
ground_truth = 3
max_organs = 2000
max_depth = 8
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
bark_color = [0.26, 0.2, 0.15]
leaf_color = [0.15, 0.32, 0.07]
)toml";
}

}  // namespace

constinit const MethodEntry kPlantonsMethod{"plantons", kKeys, skeleton_pass, builtin_preset,
                                            plantons_make_inputs};

}  // namespace forest
