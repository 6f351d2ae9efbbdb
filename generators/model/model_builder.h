// What every method does after its skeleton pass: mesh, bound, and describe the model
// (the extras.forest metadata). Shared so that all methods write the same metadata.
#pragma once
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include "generators/mesh/mesher.h"
#include "generators/model/tree_model.h"

namespace forest {

class TomlTable;

struct ModelDescription {
  std::string method;        // method id
  std::string species;       // preset name
  uint64_t seed = 0;         // the seed actually used
  nlohmann::json parameters = nlohmann::json::object();  // the species table as JSON
  glm::vec3 bark_color{0.30f, 0.22f, 0.15f};
  glm::vec3 leaf_color{0.18f, 0.35f, 0.08f};
  LeafShape leaf_shape = LeafShape::ovate;  // outline of the leaf texture and card
};

// Meshes the graph (branches + leaf card + leaves), optimizes the branch mesh for the GPU
// (vertex cache, vertex fetch), builds its simplified LODs (50%, 25%, 12% of the triangles,
// errors in meters), draws the leaf texture, computes the bounding sphere and fills meta with
// format_version, generator, method, seed, species, parameters, node_count, leaf_count,
// triangle_count, branch_lods ([{level, triangle_count, error}]), leaf_shape,
// bounding_sphere and height.
TreeModel build_tree_model(const TreeGraph& graph, const ModelDescription& description,
                           const MesherParams& mesher = {});

// While alive, every build_tree_model on this thread also copies the graph it meshes into
// *sink: how generate_from_species hands out a method's skeleton (GenerateOptions::skeleton,
// used by `forest learn`) without every method passing it along.
struct SkeletonCapture {
  explicit SkeletonCapture(TreeGraph* sink);
  ~SkeletonCapture();
  SkeletonCapture(const SkeletonCapture&) = delete;
  SkeletonCapture& operator=(const SkeletonCapture&) = delete;
  TreeGraph* previous = nullptr;
};

// Species keys ring_sides_min / ring_sides_max (shared by every method); the current values
// of `mesher` are the defaults. InputError naming the key when out of range or crossed.
void read_ring_sides(const TomlTable& species, MesherParams& mesher);

// A TOML table as JSON (dates and times as their TOML text); deterministic key order.
nlohmann::json toml_to_json(const toml::table& table);

}  // namespace forest
