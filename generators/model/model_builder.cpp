#include "generators/model/model_builder.h"

#include "generators/core/toml_reader.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "generators/core/limits.h"
#include "generators/mesh/bark_texture.h"
#include "generators/mesh/mesh_lod.h"
#include "generators/mesh/mesher.h"
#include "generators/mesh/structural_lod.h"

namespace forest {

namespace {
nlohmann::json node_to_json(const toml::node& node) {
  if (auto t = node.as_table()) return toml_to_json(*t);
  if (auto a = node.as_array()) {
    nlohmann::json out = nlohmann::json::array();
    for (const toml::node& e : *a) out.push_back(node_to_json(e));
    return out;
  }
  if (auto s = node.as_string()) return s->get();
  if (auto i = node.as_integer()) return i->get();
  if (auto f = node.as_floating_point()) return f->get();
  if (auto b = node.as_boolean()) return b->get();
  std::ostringstream text;  // date, time, date-time
  node.visit([&](auto&& v) { text << v; });
  return text.str();
}

// The bark's textures, the size of their tile (the mesher's uv are in the same tiles) and
// the pattern's name in the metadata.
void add_bark(TreeModel& model, const LookKeys& look) {
  BarkTextures bark = make_bark_textures(look.bark_pattern, look.bark_color);
  model.bark_texture = std::move(bark.albedo);
  model.bark_normal = std::move(bark.normal);
  model.bark_tile_meters = bark_tile_meters(look.bark_pattern);
  model.meta["bark_pattern"] = bark_pattern_name(look.bark_pattern);
}
}  // namespace

nlohmann::json toml_to_json(const toml::table& table) {
  nlohmann::json out = nlohmann::json::object();
  for (auto&& [key, value] : table) out[std::string(key.str())] = node_to_json(value);
  return out;
}

TreeModel build_model(const TreeGraph& graph, const LookKeys& look, const ShootDesign& shoot,
                      const ModelDescription& d) {
  if (graph.leaves.size() > kMaxLeavesPerModel)
    throw InputError(d.species, 0, "leaf_count",
                     std::to_string(graph.leaves.size()) + " leaves, more than the limit of " +
                         std::to_string(kMaxLeavesPerModel) + " per model");
  MesherParams mesher;
  mesher.min_sides = look.ring_sides_min;
  mesher.max_sides = look.ring_sides_max;
  mesher.bark_tile_meters = bark_tile_meters(look.bark_pattern);
  TreeModel model;
  BranchMeshInfo info;
  model.branches = mesh_branches(graph, mesher, &info);
  optimize_mesh(model.branches);
  model.branch_lods = structural_lods(graph, mesher, model.branches, info);
  model.leaf_card = make_foliage_card(shoot);
  model.leaf_texture = make_foliage_texture(shoot);
  model.leaves = graph.leaves;
  model.bounding_sphere = bounding_sphere(model.branches, model.leaf_card, model.leaves);
  model.bark_color = look.bark_color;
  add_bark(model, look);
  model.leaf_color = look.leaf_color;

  float height = 0.0f;
  for (const Vertex& v : model.branches.vertices) height = std::max(height, v.position.y);
  for (const LeafPlacement& l : model.leaves)
    for (const Vertex& v : model.leaf_card.vertices)
      height = std::max(height, leaf_to_model(l, v.position).y);

  nlohmann::json& m = model.meta;
  m["format_version"] = 1;
  m["generator"] = "forest";
  m["method"] = d.method;
  m["species"] = d.species;
  m["seed"] = d.seed;
  m["parameters"] = d.parameters;
  m["node_count"] = graph.nodes.size();
  m["leaf_count"] = model.leaves.size();
  m["triangle_count"] = model.branches.indices.size() / 3;
  nlohmann::json lods = nlohmann::json::array();
  for (size_t i = 0; i < model.branch_lods.size(); ++i)
    lods.push_back({{"level", i + 1},
                    {"triangle_count", model.branch_lods[i].mesh.indices.size() / 3},
                    {"error", model.branch_lods[i].error}});
  m["branch_lods"] = lods;
  m["leaf_shape"] = leaf_shape_name(look.leaf_shape);
  m["foliage"] = {{"element", shoot.single_leaf ? "leaf" : "shoot"},
                  {"leaves_per_element", shoot.single_leaf ? 1 : shoot.leaves},
                  {"card_aspect", foliage_card_aspect(shoot)}};
  const glm::vec4& s = model.bounding_sphere;
  m["bounding_sphere"] = {s.x, s.y, s.z, s.w};
  m["height"] = height;
  // A method's statistics sit beside the shared entries; overwriting one would make the
  // metadata of different methods mean different things.
  for (auto& [key, value] : d.method_meta.items()) {
    if (m.contains(key)) throw std::logic_error("method metadata '" + key + "' overwrites a shared entry");
    m[key] = value;
  }
  return model;
}

}  // namespace forest
