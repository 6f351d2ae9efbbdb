// The shared model stage: what every method's skeleton becomes. A method's skeleton pass
// spends all of its randomness and returns a Skeleton; build_model turns it, the shared look
// keys (look_keys.h) and the description into the model: branch mesh and its LOD chain, leaf
// card and texture, colours, bounds and the extras.forest metadata. A pure function of its
// inputs, so all methods write the same metadata and the same seed gives the same bytes.
#pragma once
#include <cstdint>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include "generators/mesh/foliage_card.h"
#include "generators/model/look_keys.h"
#include "generators/model/tree_model.h"

namespace forest {

// What a method's skeleton pass returns.
struct Skeleton {
  TreeGraph graph;  // radii set
  // true: the method placed its foliage elements itself (an L-system's 'L' symbols) and the
  // foliage stage only sizes and colours them; false: the foliage stage places them.
  bool own_leaves = false;
  // When set, the foliage stage calls it after placing the foliage: a method's own limit on
  // where foliage may grow (the image methods keep it inside every view's mask).
  std::function<void(TreeGraph&)> keep_leaves;
  // The method's own extras.forest entries (statistics of its run); they must not reuse a
  // key build_model writes.
  nlohmann::json meta = nlohmann::json::object();
};

// Where the model came from (the registry fills it from the species table).
struct ModelDescription {
  std::string method;   // method id
  std::string species;  // preset name
  uint64_t seed = 0;    // the seed actually used
  nlohmann::json parameters = nlohmann::json::object();   // the species table as JSON
  nlohmann::json method_meta = nlohmann::json::object();  // Skeleton::meta
};

// Meshes the graph (branches + foliage card + leaves) with the look's ring sides, optimizes the
// branch mesh for the GPU (vertex cache, vertex fetch), builds its simplified LODs (50%, 25%,
// 12% of the triangles, errors in meters), draws the foliage card and texture of `shoot`,
// sets the look's colours, computes the bounding sphere and fills meta with format_version,
// generator, method, seed, species, parameters, node_count, leaf_count, triangle_count,
// branch_lods ([{level, triangle_count, error}]), leaf_shape, foliage ({element, leaves_per_element,
// card_aspect}), bounding_sphere and height, plus
// method_meta. InputError (naming the species and key leaf_count) above kMaxLeavesPerModel.
TreeModel build_model(const TreeGraph& graph, const LookKeys& look, const ShootDesign& shoot,
                      const ModelDescription& description);

// A TOML table as JSON (dates and times as their TOML text); deterministic key order.
nlohmann::json toml_to_json(const toml::table& table);

}  // namespace forest
