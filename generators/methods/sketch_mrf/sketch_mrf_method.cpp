// Species keys of method "sketch-mrf" (all optional; ranges checked):
//   name, seed; strokes = drawing file (.json / .svg, relative to the species file; without
//   it a sketch is projected in memory from synthetic_template / synthetic_view /
//   synthetic_generations); template = "auto" (argmax of L_c + L_b) or a database name;
//   keep_omega (true: the template's Omega is kept, 4.6.1), em_iterations, interaction (k_e);
//   generations (propagation), max_segments, use_crown; tip_radius, pipe_exponent;
//   leaf_size / leaves_per_tip (default: the template's leaf model), leaf_angle;
//   ring_sides_min / ring_sides_max; bark_color / leaf_color (default: the template's).
#include "generators/methods/sketch_mrf/sketch_mrf_method.h"

#include <fstream>

#include "generators/model/model_builder.h"
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

void write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out) throw InputError(file.string(), 0, "--out", "cannot write file");
}

}  // namespace

Drawing sketch_mrf_synthetic_drawing(const std::string& template_name, int view, int generations) {
  int i = find_sketch_template(template_name);
  if (i < 0) throw InputError("", 0, "synthetic_template", "unknown template '" + template_name + "'");
  return project_template(sketch_template_database()[size_t(i)], view, generations, true);
}

TreeModel generate_sketch_mrf(const TomlTable& t, const std::string& species_name,
                              const GenerateOptions& options) {
  t.check_keys({"method", "name", "seed", "strokes", "synthetic_template", "synthetic_view",
                "synthetic_generations", "template", "keep_omega", "em_iterations", "interaction",
                "generations", "max_segments", "use_crown", "tip_radius", "pipe_exponent",
                "leaf_size", "leaves_per_tip", "leaf_angle", "ring_sides_min", "ring_sides_max",
                "bark_color", "leaf_color"});
  t.string("name", "");
  uint64_t seed = options.seed.value_or(uint64_t(t.integer("seed", 1, 0, int64_t(1) << 53)));

  Drawing drawing;
  if (t.has("strokes")) {
    std::filesystem::path file = t.string("strokes");
    if (file.is_relative()) file = std::filesystem::path(t.file()).parent_path() / file;
    if (!std::filesystem::exists(file)) t.fail("strokes", "no such file '" + file.string() + "'");
    drawing = read_drawing(file);
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
  LeafParams lp;
  lp.size = float(t.number("leaf_size", tpl.leaf_size, 0.0, 10.0));
  lp.size_jitter = 0.2f;
  lp.per_tip = int(t.integer("leaves_per_tip", tpl.leaves_per_tip, 0, 16));
  lp.angle_deg = float(t.number("leaf_angle", 45.0, 0.0, 180.0));
  if (lp.size > 0.0f) place_twig_leaves(graph, lp, seed);

  MesherParams mesher;
  mesher.min_sides = 3;
  mesher.max_sides = 8;
  read_ring_sides(t, mesher);

  ModelDescription d;
  d.method = "sketch-mrf";
  d.species = t.string("name", species_name);
  d.seed = seed;
  d.parameters = toml_to_json(t.raw());
  d.bark_color = t.vec3("bark_color", tpl.bark_color, 0.0, 1.0);
  d.leaf_color = t.vec3("leaf_color", tpl.leaf_color, 0.0, 1.0);
  TreeModel model = build_tree_model(graph, d, mesher);
  nlohmann::json& info = model.meta["sketch_mrf"];
  info["template"] = tpl.name;
  info["template_view"] = choice.view;
  info["sketch_segments"] = sketch.xy.size() - 1;
  info["em_iterations"] = inferred.em_iterations;
  info["propagated_segments"] = grown.position.size() - sketch.xy.size();
  info["closed_by_crown"] = grown.closed_by_crown;
  return model;
}

const char* sketch_mrf_default_species_text() {
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
)toml";
}

void sketch_mrf_make_inputs(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(dir.string(), 0, "--out", "cannot create folder: " + ec.message());
  Drawing maple = sketch_mrf_synthetic_drawing("broadleaf", 1, 3);
  write_text(dir / "maple.json", drawing_to_json(maple));
  write_text(dir / "maple.svg", drawing_to_svg(maple));
  write_text(dir / "pine.json", drawing_to_json(sketch_mrf_synthetic_drawing("conifer", 2, 2)));
  write_text(dir / "umbrella.json", drawing_to_json(sketch_mrf_synthetic_drawing("umbrella", 3, 3)));
}

}  // namespace forest
