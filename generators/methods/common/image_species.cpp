#include "generators/methods/common/image_species.h"

#include <filesystem>

#include "generators/methods/common/image_synthetic.h"
#include "generators/methods/common/image_tree_util.h"
#include "generators/tree/pipe_model.h"

namespace forest {

void check_image_species_keys(const TomlTable& t, std::initializer_list<std::string_view> own) {
  for (auto&& [k, v] : t.raw()) {
    std::string_view key = k.str();
    bool ok = key == "method" || key == "name" || key == "seed";
    for (auto a : own) ok = ok || a == key;
    for (auto a : kImageInputKeys) ok = ok || a == key;
    for (auto a : kTreeLookKeys) ok = ok || a == key;
    if (!ok) {
      std::string list = "method, name, seed";
      for (auto a : own) list += ", " + std::string(a);
      for (auto a : kImageInputKeys) list += ", " + std::string(a);
      for (auto a : kTreeLookKeys) list += ", " + std::string(a);
      throw InputError(t.file(), int(k.source().begin.line), std::string(key),
                       "unknown key (expected one of: " + list + ")");
    }
  }
}

ViewSet read_image_input(const TomlTable& t) {
  if (t.has("views") == t.has("crown"))
    t.fail(t.has("views") ? "crown" : "views", "give exactly one of `views` (a views.json file) or `crown` (synthetic)");
  if (auto crown = t.table("crown")) return synthesize_view_set(read_crown_spec(*crown));
  std::string rel = t.string("views");
  std::filesystem::path base = std::filesystem::path(t.file()).parent_path();
  std::filesystem::path file = base / rel;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) t.fail("views", "file not found: " + file.string());
  return load_view_set(file);
}

TreeLook read_tree_look(const TomlTable& t, const TreeLook& d) {
  TreeLook s = d;
  s.tip_radius = float(t.number("tip_radius", d.tip_radius, 1e-5, 1.0));
  s.pipe_exponent = float(t.number("pipe_exponent", d.pipe_exponent, 1.0, 4.0));
  s.leaves.size = float(t.number("leaf_size", d.leaves.size, 0.0, 10.0));
  s.leaves.size_jitter = float(t.number("leaf_size_jitter", d.leaves.size_jitter, 0.0, 0.9));
  s.leaves.angle_deg = float(t.number("leaf_angle", d.leaves.angle_deg, 0.0, 180.0));
  s.leaves.angle_jitter_deg = float(t.number("leaf_angle_jitter", d.leaves.angle_jitter_deg, 0.0, 90.0));
  s.leaves.per_tip = int(t.integer("leaves_per_tip", d.leaves.per_tip, 0, 16));
  s.leaves.along = int(t.integer("leaves_along", d.leaves.along, 0, 16));
  s.mesher.min_sides = d.mesher.min_sides;
  s.mesher.max_sides = d.mesher.max_sides;
  read_ring_sides(t, s.mesher);
  s.bark_color = t.vec3("bark_color", d.bark_color, 0.0, 1.0);
  s.leaf_color = t.vec3("leaf_color", d.leaf_color, 0.0, 1.0);
  return s;
}

TreeModel finish_image_tree(TreeGraph graph, const TreeLook& look, const ViewSet& views,
                            const TomlTable& root, const std::string& method,
                            const std::string& species_name, uint64_t seed,
                            const nlohmann::json& extra) {
  assign_pipe_radii(graph, look.tip_radius, look.pipe_exponent);
  if (look.leaves.size > 0.0f) {
    place_twig_leaves(graph, look.leaves, seed);
    drop_leaves_outside_masks(graph, views);
  }
  ModelDescription d;
  d.method = method;
  d.species = root.string("name", species_name);
  d.seed = seed;
  d.parameters = toml_to_json(root.raw());
  d.bark_color = look.bark_color;
  d.leaf_color = look.leaf_color;
  TreeModel model = build_tree_model(graph, d, look.mesher);
  model.meta["method_stats"] = extra;
  return model;
}

}  // namespace forest
