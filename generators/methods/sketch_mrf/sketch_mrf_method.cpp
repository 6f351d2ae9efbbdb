// Species keys of method "sketch-mrf" (all optional; ranges checked):
//   name, seed; strokes = drawing file (.json / .svg, relative to the species file; without
//   it a sketch is projected in memory from synthetic_template / synthetic_view /
//   synthetic_generations); template = "auto" (argmax of L_c + L_b) or a database name;
//   keep_omega (true: the template's Omega is kept, 4.6.1), em_iterations, interaction (k_e);
//   generations (propagation), max_segments, use_crown; tip_radius, pipe_exponent; plus the
//   shared look keys (model/look_keys.h) and foliage keys (tree/foliage.h).
#include "generators/methods/sketch_mrf/sketch_mrf_method.h"

#include "generators/methods/sketch_mrf/sketch_mrf_inference.h"
#include "generators/methods/sketch_mrf/sketch_propagation.h"
#include "generators/methods/sketch_mrf/sketch_templates.h"
#include "generators/tree/leaves.h"
#include "generators/tree/pipe_model.h"

namespace forest {

namespace {

std::string template_names() {
  std::string s;
  for (const SketchTemplate& t : sketch_template_database()) s += (s.empty() ? "" : ", ") + t.name;
  return s;
}

int template_key(const TomlTable& t, std::string_view key, const std::string& fallback) {
  std::string name = t.string(key, fallback);
  int i = find_sketch_template(name);
  if (i < 0) t.fail(key, "unknown template '" + name + "' (known: " + template_names() + ")");
  return i;
}

}  // namespace

Drawing sketch_mrf_synthetic_drawing(const std::string& template_name, int view, int generations) {
  int i = find_sketch_template(template_name);
  if (i < 0) throw InputError("", 0, "synthetic_template", "unknown template '" + template_name + "'");
  return project_template(sketch_template_database()[size_t(i)], view, generations, true);
}

namespace {

// The method's own species keys; the registry adds the common and the look keys.
constexpr std::string_view kKeys[] = {
    "strokes", "synthetic_template", "synthetic_view", "synthetic_generations", "template",
    "keep_omega", "em_iterations", "interaction", "generations", "max_segments", "use_crown",
    "tip_radius", "pipe_exponent"};

Skeleton skeleton_pass(const TomlTable& t, uint64_t seed) {

  Drawing drawing;
  if (t.has("strokes")) {
    drawing = read_drawing(t.existing_file("strokes"));
  } else {
    int ti = template_key(t, "synthetic_template", "broadleaf");
    int view = int(t.integer("synthetic_view", 1, 0, kTemplateViews - 1));
    int gens = int(t.integer("synthetic_generations", 3, 1, 4));
    drawing = project_template(sketch_template_database()[size_t(ti)], view, gens, true);
  }
  SketchTree sketch = sketch_tree_from_drawing(drawing);

  TemplateChoice choice;
  std::string tname = t.string("template", "auto");
  if (tname == "auto") {
    choice = choose_template(sketch);
  } else {
    choice.index = template_key(t, "template", "auto");
  }
  const SketchTemplate& tpl = sketch_template_database()[size_t(choice.index)];

  InferenceParams ip;
  ip.estimate_omega = !t.boolean("keep_omega", false);
  ip.em_iterations = int(t.integer("em_iterations", 8, 1, 20));
  ip.k_e = t.number("interaction", 5.0, 0.0, 100.0);
  InferenceResult inferred = infer_depths(sketch, tpl.omega, ip);

  PropagationParams pp;
  pp.generations = int(t.integer("generations", 5, 0, 8));
  pp.max_segments = size_t(t.integer("max_segments", 30000, 10, 200000));
  bool use_crown = t.boolean("use_crown", true) && sketch.crown.size() >= 3;
  CrownSurface crown{sketch.crown, sketch.xy[0].x};
  PropagatedTree grown = propagate_branches(sketch, inferred.depths, use_crown ? &crown : nullptr, pp, seed);

  TreeGraph graph;
  glm::dvec3 origin = grown.position[0];
  for (size_t i = 0; i < grown.position.size(); ++i) {
    TreeNode n;
    n.position = glm::vec3(grown.position[i] - origin);
    n.parent = grown.parent[i];
    n.order = grown.order[i];
    graph.nodes.push_back(n);
  }
  assign_pipe_radii(graph, float(t.number("tip_radius", 0.01, 1e-5, 1.0)),
                    float(t.number("pipe_exponent", 2.3, 1.0, 4.0)));

  Skeleton out{std::move(graph)};
  nlohmann::json& info = out.meta["sketch_mrf"];
  info["template"] = tpl.name;
  info["template_view"] = choice.view;
  info["sketch_segments"] = sketch.xy.size() - 1;
  info["em_iterations"] = inferred.em_iterations;
  info["propagated_segments"] = grown.position.size() - sketch.xy.size();
  info["closed_by_crown"] = grown.closed_by_crown;
  return out;
}

const char* builtin_preset() {
  return R"toml(method = "sketch-mrf"
# Built-in preset: a sketch projected in memory from the "broadleaf" template (3 stroke
# levels and its crown curve), then template choice, depth inference and propagation.
name = "sketch_mrf"
seed = 1
synthetic_template = "broadleaf"
synthetic_view = 1
synthetic_generations = 3
template = "auto"
generations = 3
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
bark_color = [0.20, 0.15, 0.11]
leaf_color = [0.13, 0.30, 0.05]
)toml";
}

// Writes dir/maple.json, dir/pine.json (strokes with ground-truth depths and a crown
// curve) and dir/maple.svg (the same strokes as SVG polylines).
void write_inputs(const std::filesystem::path& dir) {
  Drawing maple = sketch_mrf_synthetic_drawing("broadleaf", 1, 3);
  Drawing pine = sketch_mrf_synthetic_drawing("conifer", 2, 2);
  Drawing umbrella = sketch_mrf_synthetic_drawing("umbrella", 3, 3);
  write_drawing_files(dir, {{"maple.json", drawing_to_json(maple)},
                            {"maple.svg", drawing_to_svg(maple)},
                            {"pine.json", drawing_to_json(pine)},
                            {"umbrella.json", drawing_to_json(umbrella)}});
}

}  // namespace

constinit const MethodEntry kSketchMrfMethod{"sketch-mrf", kKeys, skeleton_pass, builtin_preset,
                                             write_inputs};

}  // namespace forest
